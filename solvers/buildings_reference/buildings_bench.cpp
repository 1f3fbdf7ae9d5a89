// Cost of one solve of the buildings' exact reference (solvers/buildings_reference/): the
// issue's 3 + 3 storey pair under a sine pulse, pounding and not, and taller pairs.

#include <benchmark/benchmark.h>

#include <vector>

#include "cases/buildings.hpp"
#include "solvers/buildings_reference/reference.hpp"

namespace {

pb::Building building(std::vector<double> m, std::vector<double> k) { return {std::move(m), std::move(k)}; }

// The issue's two buildings (3 storeys each, SI units), 5 % Rayleigh damping, eps 0.6, a
// sine pulse of 3 m/s^2 at 2 Hz, gap in mm.
pb::BuildingScene issue_scene(double gap_mm) {
  pb::BuildingScene s;
  s.buildings = {building({3e5, 3e5, 2.4e5}, {6.8e8, 5.4e8, 4.1e8}),
                 building({2.5e5, 2.5e5, 2e5}, {2.0e8, 1.6e8, 1.2e8})};
  s.xi = 0.05;
  s.delta = gap_mm * 1e-3;
  s.eps = 0.6;
  s.pulse = pb::Pulse(pb::PulseShape::sine, 3.0, 12.566);
  return s;
}

void time_solve(benchmark::State& state, const pb::BuildingScene& scene) {
  const pb::BuildingModel model = pb::assemble(scene);
  long events = 0, impacts = 0;
  for (auto _ : state) {
    const pb::buildings::BuildingsResult r = pb::buildings::solve(model);
    events = r.events;
    impacts = 0;
    for (const auto& c : r.contacts) impacts += c.impacts;
    if (r.status != pb::Status::ok) state.SkipWithError(r.message.c_str());
    benchmark::DoNotOptimize(r.floor_peak);
  }
  state.counters["events"] = static_cast<double>(events);
  state.counters["impacts"] = static_cast<double>(impacts);
}

// Gap 0 (touching at rest), 5 mm and 30 mm (the issue's), and 1 m (no pounding).
void BM_BuildingsIssuePair(benchmark::State& state) { time_solve(state, issue_scene(static_cast<double>(state.range(0)))); }
BENCHMARK(BM_BuildingsIssuePair)->ArgName("gap_mm")->Arg(0)->Arg(5)->Arg(30)->Arg(1000)->Unit(benchmark::kMicrosecond);

// Uniform pairs of n + 2n storeys by their Pi terms: Pi2 = 1, Pi3 = 0.5, eps 0.5, Pi5 = 2
// (the left building the stiffer), Pi6 = 1.
void BM_BuildingsUniformPair(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const pb::Pulse pulse(pb::PulseShape::sine, 1.0, 1.0);
  time_solve(state, pb::uniform_pair(n, 2 * n, 1.0, 0.5, 0.5, 2.0, 1.0, pulse, 1.0, 1.0));
}
BENCHMARK(BM_BuildingsUniformPair)->ArgName("floors")->Arg(3)->Arg(10)->Unit(benchmark::kMicrosecond);

}  // namespace
