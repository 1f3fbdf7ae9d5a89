// Cost of the ODE solver per run and per step, for each variant on wall, pair and row3
// (Pi2 = 1, Pi3 = 0.5, Pi5 = Pi7 = 0.5, Pi6 = Pi8 = 1, eps = 0.5, cosine, normal) at
// N = 64 and 256, against moreau_jean::solve on the same cases.
//
// Counters: time_per_step (CPU seconds per step), steps, impacts, and x_moreau_jean: the
// CPU time of one run over that of moreau_jean::solve on the same case and N, measured
// right after the timed loop so that both see the same machine load (the library prints
// it with an "s" because it is an inverted rate; read it as a plain ratio).
// BM_OdeBaselineMoreauJean times the baseline on its own as well.
//
// BM_OdeChain/bodies:<n>: the default variant on a chain of n = 2 .. 100 bodies,
// alternating (odd bodies Pi5 = 0.5, Pi6 = 1) with a gap (Pi3 = 0.5) under the cosine
// pulse (Pi2 = 1, eps = 0.5), N = 64: the cost per step against n (counters
// time_per_step, time_per_body_step, steps, impacts).
// Run with --benchmark_repetitions=9 (or more) and read the medians.

#include <benchmark/benchmark.h>

#include "bench/support.hpp"
#include "cases/system.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "solvers/ode/ode_solver.hpp"

namespace {

void BM_Ode(benchmark::State& state, const char* variant, pb::Scene scene) {
  pb::bench::time_variant(state, &pb::ode::solve, variant, scene, static_cast<int>(state.range(0)));
  pb::Settings in_house;
  in_house.steps = static_cast<int>(state.range(0));
  state.counters["x_moreau_jean"] =
      pb::bench::ratio_to(pb::bench::seconds_per_run(&pb::moreau_jean::solve, pb::bench::fig4_point(scene), in_house));
}

void BM_OdeChain(benchmark::State& state) { pb::bench::time_chain(state, &pb::ode::solve); }

void BM_OdeBaselineMoreauJean(benchmark::State& state, pb::Scene scene) {
  pb::bench::time_solve(state, &pb::moreau_jean::solve, scene);
}

#define PB_ODE_BENCH(fn, label, ...) \
  BENCHMARK_CAPTURE(fn, label, __VA_ARGS__)->ArgName("N")->Arg(64)->Arg(256)->Unit(benchmark::kMicrosecond)

PB_ODE_BENCH(BM_Ode, dantzig_faithful_wall, "dantzig-faithful", pb::Scene::wall);
PB_ODE_BENCH(BM_Ode, dantzig_faithful_pair, "dantzig-faithful", pb::Scene::pair);
PB_ODE_BENCH(BM_Ode, dantzig_faithful_row3, "dantzig-faithful", pb::Scene::row3);
PB_ODE_BENCH(BM_Ode, dantzig_default_wall, "dantzig-default", pb::Scene::wall);
PB_ODE_BENCH(BM_Ode, dantzig_default_pair, "dantzig-default", pb::Scene::pair);
PB_ODE_BENCH(BM_Ode, dantzig_default_row3, "dantzig-default", pb::Scene::row3);
PB_ODE_BENCH(BM_Ode, quickstep_faithful_wall, "quickstep-faithful", pb::Scene::wall);
PB_ODE_BENCH(BM_Ode, quickstep_faithful_pair, "quickstep-faithful", pb::Scene::pair);
PB_ODE_BENCH(BM_Ode, quickstep_faithful_row3, "quickstep-faithful", pb::Scene::row3);
PB_ODE_BENCH(BM_Ode, quickstep_default_wall, "quickstep-default", pb::Scene::wall);
PB_ODE_BENCH(BM_Ode, quickstep_default_pair, "quickstep-default", pb::Scene::pair);
PB_ODE_BENCH(BM_Ode, quickstep_default_row3, "quickstep-default", pb::Scene::row3);
PB_ODE_BENCH(BM_OdeBaselineMoreauJean, wall, pb::Scene::wall);
PB_ODE_BENCH(BM_OdeBaselineMoreauJean, pair, pb::Scene::pair);
PB_ODE_BENCH(BM_OdeBaselineMoreauJean, row3, pb::Scene::row3);

BENCHMARK(BM_OdeChain)->ArgName("bodies")->Arg(2)->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
