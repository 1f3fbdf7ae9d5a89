// Cost of the Siconos solver per run and per step, on wall, pair and row3 at the Fig. 4 point
// of bench/support.hpp (Pi2 = 1, Pi3 = 0.5, Pi5 = Pi7 = 0.5, Pi6 = Pi8 = 1, eps = 0.5,
// cosine, normal), against the in-house solvers on the same cases. Empty unless CMake finds
// Siconos (POUNDBENCH_HAVE_SICONOS), as bullet_bench.cpp is without Bullet.
//
//   BM_Siconos/<variant>_<scene>/N           moreau-jean-lemke and moreau-jean-enum, N = 64, 256:
//                                            one pb::siconos::solve per iteration (the model and
//                                            simulation set-up included: part of every run)
//   BM_SiconosEventDriven/<scene>             event-driven-lsodar
//   BM_SiconosChain/bodies:<n>                moreau-jean-lemke on a chain of n bodies,
//                                            alternating (odd bodies Pi5 = 0.5, Pi6 = 1) with
//                                            a gap, N = 64: cost per step against n
//   BM_SiconosBaselineMoreauJean/<scene>/N   moreau_jean::solve alone
//
// Counters: time_per_step (CPU seconds per step; per event for the event-driven variant),
// steps, impacts, and the ratio of CPU time per run to the in-house solver's on the same case
// (x_moreau_jean: moreau-jean, default settings, same N; x_event_driven: the event-driven
// reference), measured right after the timed loop so that both see the same machine load
// (printed with an "s": an inverted rate; read it as a plain ratio).
// Run with --benchmark_repetitions=9 (or more) and read the medians.

#ifdef POUNDBENCH_HAVE_SICONOS

#include <benchmark/benchmark.h>

#include "bench/support.hpp"
#include "cases/system.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "solvers/siconos/siconos_solver.hpp"

namespace {

using pb::bench::ratio_to;
using pb::bench::seconds_per_run;

const bool registered = pb::bench::register_vs_moreau_jean(
    "BM_Siconos", &pb::siconos::solve, {{"lemke", "moreau-jean-lemke"}, {"enum", "moreau-jean-enum"}});

void BM_SiconosEventDriven(benchmark::State& state, pb::Scene scene) {
  pb::bench::time_variant(state, &pb::siconos::solve, "event-driven-lsodar", scene, 0);
  state.counters["x_event_driven"] =
      ratio_to(seconds_per_run(&pb::event_driven::solve, pb::bench::fig4_point(scene), {}));
}

void BM_SiconosChain(benchmark::State& state) {
  pb::bench::time_chain(state, &pb::siconos::solve);
  const pb::System s = pb::bench::chain_point(static_cast<int>(state.range(0)));
  state.counters["x_moreau_jean"] = ratio_to(seconds_per_run(&pb::moreau_jean::solve, s, {}));
}

BENCHMARK_CAPTURE(BM_SiconosEventDriven, wall, pb::Scene::wall)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SiconosEventDriven, pair, pb::Scene::pair)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SiconosEventDriven, row3, pb::Scene::row3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SiconosChain)->ArgName("bodies")->Arg(2)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond);

}  // namespace

#endif  // POUNDBENCH_HAVE_SICONOS
