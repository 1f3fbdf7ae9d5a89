// Cost of one Moreau-Jean solve of the buildings scene (solvers/moreau_jean/buildings.hpp), set-up
// included: the issue's 3 + 3 storey pair (a 30 mm gap, and 5 mm where floors stick), and a
// uniform 20 + 20 storey pair (a gap of 0.5 a_p / w_p^2, and none). Counters: steps per run,
// impacts, and time_per_floor_step (CPU seconds per step and floor, the scaling measure: a step
// costs sparse products and a banded solve linear in the floors, plus the LCP where contacts
// are active). Run with --benchmark_repetitions=9 (or more) and read the medians.

#include <benchmark/benchmark.h>

#include <vector>

#include "cases/buildings.hpp"
#include "kit/benchmarking.hpp"
#include "kit/testing_buildings.hpp"
#include "solvers/moreau_jean/buildings.hpp"

namespace {

void time_solve(benchmark::State& state, const pb::BuildingScene& scene, int steps_per_period) {
  const pb::BuildingModel model = pb::assemble(scene);
  pb::Settings settings = pb::bench::timed({});
  settings.steps = steps_per_period;
  long steps = 0, impacts = 0;
  for (auto _ : state) {
    const pb::buildings::BuildingsResult r = pb::moreau_jean::solve_buildings(model, settings);
    steps = r.events;
    impacts = 0;
    for (const auto& c : r.contacts) impacts += c.impacts;
    if (r.status != pb::Status::ok) state.SkipWithError(r.message.c_str());
    benchmark::DoNotOptimize(r.floor_peak);
  }
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["impacts"] = static_cast<double>(impacts);
  state.counters["time_per_floor_step"] = pb::bench::per_step(steps * model.n_floors);
}

// The issue's pair at N = 64 (its default step), gap in mm.
void BM_MoreauJeanBuildingsIssuePair(benchmark::State& state) {
  pb::BuildingScene s = pb::test::issue_scene();
  s.delta = static_cast<double>(state.range(0)) * 1e-3;
  time_solve(state, s, 64);
}
BENCHMARK(BM_MoreauJeanBuildingsIssuePair)->ArgName("gap_mm")->Arg(30)->Arg(5)->Unit(benchmark::kMicrosecond);

// A uniform 20 + 20 storey pair by its Pi terms (Pi2 = 0.5, eps 0.5, Pi5 = 2, Pi6 = 1) at N = 64,
// gap Pi3 = range / 10.
void BM_MoreauJeanBuildingsTallPair(benchmark::State& state) {
  const pb::Pulse pulse(pb::PulseShape::sine, 1.0, 1.0);
  const double pi3 = static_cast<double>(state.range(0)) / 10.0;
  time_solve(state, pb::uniform_pair(20, 20, 0.5, pi3, 0.5, 2.0, 1.0, pulse, 1.0, 1.0), 64);
}
BENCHMARK(BM_MoreauJeanBuildingsTallPair)->ArgName("pi3x10")->Arg(5)->Arg(0)->Unit(benchmark::kMicrosecond);

}  // namespace
