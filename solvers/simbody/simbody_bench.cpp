// Cost of the Simbody solver per run and per step: its time-stepper's variants on wall, pair
// and row3 (the ODE benchmark's cases: Pi2 = 1, Pi3 = 0.5, Pi5 = Pi7 = 0.5, Pi6 = Pi8 = 1,
// eps = 0.5, cosine, normal) at N = 64, against moreau_jean::solve on the same cases; and its
// Hunt-Crossley elements on the same cases, against the compliant solver's own Hunt-Crossley
// element through CVODE (both at K = 1e4 and their default tolerances).
//
// Counters as in ode_bench.cpp: time_per_step, steps, impacts, and x_moreau_jean, the run's
// CPU time over moreau_jean::solve's on the same case and N, measured right after the timed
// loop; BM_SimbodyHuntCrossley has x_compliant instead (no steps of its own to count). N = 64
// only: a step's cost does not depend on N, and the main job runs every benchmark.
// Run with --benchmark_repetitions=9 (or more) and read the medians.

#ifdef POUNDBENCH_HAVE_SIMBODY

#include <benchmark/benchmark.h>

#include "kit/benchmarking.hpp"
#include "solvers/moreau_jean/versus.hpp"
#include "solvers/simbody/simbody_solver.hpp"
#ifdef POUNDBENCH_HAVE_SUNDIALS
#include "solvers/compliant/compliant.hpp"
#endif

namespace {

const bool simbody_registered = pb::bench::register_vs_moreau_jean(
    "BM_Simbody", &pb::simbody::solve,
    {{"plus_faithful", "plus-faithful"}, {"pgs_faithful", "pgs-faithful"}, {"default", "default"}}, {64});

void BM_SimbodyHuntCrossley(benchmark::State& state, pb::Scene scene) {
  const pb::Result r = pb::bench::time_variant(state, &pb::simbody::solve, "hunt-crossley", scene, 0);
  (void)r;
#ifdef POUNDBENCH_HAVE_SUNDIALS
  pb::Settings in_house;
  in_house.variant = "hunt-crossley";
  state.counters["x_compliant"] =
      pb::bench::ratio_to(pb::bench::seconds_per_run(&pb::compliant::solve, pb::bench::fig4_point(scene), in_house));
#endif
}
BENCHMARK_CAPTURE(BM_SimbodyHuntCrossley, wall, pb::Scene::wall)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SimbodyHuntCrossley, pair, pb::Scene::pair)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SimbodyHuntCrossley, row3, pb::Scene::row3)->Unit(benchmark::kMillisecond);

}  // namespace

#endif  // POUNDBENCH_HAVE_SIMBODY
