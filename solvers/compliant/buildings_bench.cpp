// Cost of one solve of the buildings scene by the compliant solver (solvers/compliant/buildings.hpp):
// the issue's 3 + 3 storey pair (kit/testing_buildings.hpp: its 30 mm gap, and 5 mm, where it
// pounds at every floor), Kelvin-Voigt elements at the default K = 1e4, through CVODE (its
// default rtol 1e-8) and Newmark (N = 64, the default, and 1024). Counters: steps (CVODE's
// internal ones, or Newmark's), impacts over every contact, and x_reference, the run's time
// over the exact reference's on the same scene (CPU time), measured right after the timed loop.

#ifdef POUNDBENCH_HAVE_SUNDIALS

#include <benchmark/benchmark.h>

#include "cases/buildings.hpp"
#include "kit/benchmarking.hpp"
#include "kit/testing_buildings.hpp"
#include "solvers/buildings_reference/reference.hpp"
#include "solvers/compliant/buildings.hpp"

// Named, not anonymous: the unity build puts this file beside the reference's benchmark.
namespace compliant_buildings_bench {

// CPU seconds per solve of the exact reference, over batches lasting about 0.02 s.
double reference_seconds(const pb::BuildingModel& model) {
  long runs = 0;
  const double start = pb::bench::thread_seconds();
  double elapsed = 0.0;
  for (long batch = 1; elapsed < 0.02; batch *= 2) {
    for (long k = 0; k < batch; ++k) benchmark::DoNotOptimize(pb::buildings::solve(model).events);
    runs += batch;
    elapsed = pb::bench::thread_seconds() - start;
  }
  return elapsed / static_cast<double>(runs);
}

void time_compliant(benchmark::State& state, const char* integrator, int steps) {
  pb::BuildingScene scene = pb::test::issue_scene();
  scene.delta = static_cast<double>(state.range(0)) * 1e-3;
  const pb::BuildingModel model = pb::assemble(scene);
  pb::Settings settings;
  settings.integrator = integrator;
  settings.steps = steps;
  long events = 0, impacts = 0;
  for (auto _ : state) {
    const pb::buildings::BuildingsResult r = pb::compliant::solve_buildings(model, settings);
    if (r.status != pb::Status::ok) state.SkipWithError(r.message.c_str());
    events = r.events;
    impacts = 0;
    for (const auto& c : r.contacts) impacts += c.impacts;
    benchmark::DoNotOptimize(r.floor_peak);
  }
  state.counters["steps"] = static_cast<double>(events);
  state.counters["impacts"] = static_cast<double>(impacts);
  state.counters["x_reference"] = pb::bench::ratio_to(reference_seconds(model));
}

void BM_CompliantBuildingsCvode(benchmark::State& state) { time_compliant(state, "cvode", 0); }
BENCHMARK(BM_CompliantBuildingsCvode)->ArgName("gap_mm")->Arg(30)->Arg(5)->Unit(benchmark::kMicrosecond);

void BM_CompliantBuildingsNewmark(benchmark::State& state) {
  time_compliant(state, "newmark", static_cast<int>(state.range(1)));
}
BENCHMARK(BM_CompliantBuildingsNewmark)
    ->ArgNames({"gap_mm", "N"})
    ->Args({30, 64})
    ->Args({30, 1024})
    ->Args({5, 64})
    ->Unit(benchmark::kMicrosecond);

}  // namespace compliant_buildings_bench

#endif  // POUNDBENCH_HAVE_SUNDIALS
