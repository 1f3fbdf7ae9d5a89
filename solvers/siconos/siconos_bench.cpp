// Cost of the Siconos solver per run and per step, on wall, pair and row3 at the Fig. 4 point
// of kit/benchmarking.hpp (Pi2 = 1, Pi3 = 0.5, Pi5 = Pi7 = 0.5, Pi6 = Pi8 = 1, eps = 0.5,
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
//   BM_SiconosScheme/<variant>_<scene>/N:64  Siconos' other integrators that run these cases
//                                            (schatzman-paoli, d1-minus-linear,
//                                            combined-projection, direct-projection), N = 64
//                                            only: a step's cost does not grow with N
//                                            (moreau-jean-lemke's at N = 64 and 256 differ by
//                                            less than 25 %, solvers/siconos/README.md), and
//                                            the main job times every benchmark
//
// Counters: time_per_step (CPU seconds per step; per event for the event-driven variant),
// steps, impacts, and the ratio of CPU time per run to the in-house solver's on the same case
// (x_moreau_jean: moreau-jean, default settings, same N; x_event_driven: the event-driven
// reference; for BM_SiconosScheme also x_siconos_moreau_jean: Siconos' own MoreauJeanOSI,
// moreau-jean-lemke at the same N, what the scheme costs over the integrator it extends),
// measured right after the timed loop so that both see the same machine load (printed with
// an "s": an inverted rate; read it as a plain ratio). bilbao and newmark-alpha are not
// timed: their runs fail (solvers/siconos/README.md), and a failed run's cost means nothing.
// Run with --benchmark_repetitions=9 (or more) and read the medians.

#ifdef POUNDBENCH_HAVE_SICONOS

#include <benchmark/benchmark.h>

#include "kit/benchmarking.hpp"
#include "solvers/moreau_jean/versus.hpp"
#include "cases/system.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "solvers/siconos/siconos_solver.hpp"

namespace {

using pb::bench::ratio_to;
using pb::bench::seconds_per_run;

const bool siconos_registered = pb::bench::register_vs_moreau_jean(
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

void BM_SiconosScheme(benchmark::State& state, const char* variant, pb::Scene scene) {
  const double own = pb::bench::time_vs_moreau_jean(state, &pb::siconos::solve, variant, scene);
  pb::Settings lemke;
  lemke.variant = "moreau-jean-lemke";
  lemke.steps = static_cast<int>(state.range(0));
  state.counters["x_siconos_moreau_jean"] =
      ratio_to(seconds_per_run(&pb::siconos::solve, pb::bench::fig4_point(scene), lemke, own));
}

const bool schemes_registered = [] {
  const pb::bench::Labelled schemes[] = {{"schatzman_paoli", "schatzman-paoli"},
                                         {"d1_minus_linear", "d1-minus-linear"},
                                         {"combined_projection", "combined-projection"},
                                         {"direct_projection", "direct-projection"}};
  for (const pb::bench::Labelled& v : schemes)
    for (pb::Scene scene : {pb::Scene::wall, pb::Scene::pair, pb::Scene::row3}) {
      const std::string title = "BM_SiconosScheme/" + std::string(v.label) + "_" + std::string(pb::name(scene));
      benchmark::RegisterBenchmark(title.c_str(), [v, scene](benchmark::State& state) {
        BM_SiconosScheme(state, v.variant, scene);
      })->ArgName("N")->Arg(64)->Unit(benchmark::kMicrosecond);
    }
  return true;
}();

BENCHMARK_CAPTURE(BM_SiconosEventDriven, wall, pb::Scene::wall)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SiconosEventDriven, pair, pb::Scene::pair)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SiconosEventDriven, row3, pb::Scene::row3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SiconosChain)->ArgName("bodies")->Arg(2)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond);

}  // namespace

#endif  // POUNDBENCH_HAVE_SICONOS
