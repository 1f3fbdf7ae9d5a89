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

#include <ctime>
#include <string>

#include "bench/support.hpp"
#include "cases/system.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "solvers/ode/ode_solver.hpp"

namespace {

// Thread CPU seconds, what the benchmark library divides rate counters by.
double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// CPU seconds per moreau_jean::solve run of the same system, over >= 20 ms, measured on
// every call right after the ODE loop, so that both see the same machine load.
double baseline_seconds(const pb::System& s, int n) {
  pb::Settings settings;
  settings.steps = n;
  long runs = 0;
  const double start = cpu_now();
  double elapsed = 0.0;
  do {
    const pb::Result r = pb::moreau_jean::solve(s, settings);
    benchmark::DoNotOptimize(r.pi1);
    ++runs;
    elapsed = cpu_now() - start;
  } while (elapsed < 0.02);
  return elapsed / static_cast<double>(runs);
}

void BM_Ode(benchmark::State& state, const char* variant, pb::Scene scene) {
  const pb::System s = pb::bench::fig4_point(scene);
  pb::Settings settings;
  settings.variant = variant;
  settings.steps = static_cast<int>(state.range(0));
  pb::Result r;
  for (auto _ : state) {
    r = pb::ode::solve(s, settings);
    benchmark::DoNotOptimize(r.pi1);
  }
  if (r.status != pb::Status::ok) state.SkipWithError(r.message.c_str());
  state.counters["time_per_step"] = pb::bench::per_step(r.steps);
  state.counters["steps"] = static_cast<double>(r.steps);
  state.counters["impacts"] = static_cast<double>(r.impacts);
  // CPU time per run over the baseline's: an inverted rate of (baseline seconds) per run.
  state.counters["x_moreau_jean"] =
      benchmark::Counter(baseline_seconds(s, settings.steps),
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

pb::System chain_point(int bodies) {
  pb::Case c;
  c.scene = pb::Scene::chain;
  c.bodies = bodies;
  c.pulse = pb::PulseShape::cosine;
  c.pi2 = 1.0;
  c.pi3 = 0.5;
  c.pi5 = 0.5;
  c.pi6 = 1.0;
  c.eps = 0.5;
  return pb::make_system(c);
}

void BM_OdeChain(benchmark::State& state) {
  const int bodies = static_cast<int>(state.range(0));
  const pb::System s = chain_point(bodies);
  pb::Result r;
  for (auto _ : state) {
    r = pb::ode::solve(s, pb::Settings{});
    benchmark::DoNotOptimize(r.pi1);
  }
  if (r.status != pb::Status::ok) state.SkipWithError(r.message.c_str());
  state.counters["time_per_step"] = pb::bench::per_step(r.steps);
  state.counters["time_per_body_step"] = pb::bench::per_step(r.steps * bodies);
  state.counters["steps"] = static_cast<double>(r.steps);
  state.counters["impacts"] = static_cast<double>(r.impacts);
}

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
