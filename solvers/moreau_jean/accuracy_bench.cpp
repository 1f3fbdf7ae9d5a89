// Time to a given accuracy: the in-house Moreau-Jean stepper at the smallest N (doubling
// from 16) whose median relative Pi1 error over the Fig. 4 family is <= 1e-3, against the
// reference on the same points, in one benchmark run so that the ratio is fair.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "kit/benchmarking.hpp"
#include "cases/system.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"

namespace {

struct Fig4 {
  std::vector<pb::System> systems;
  std::vector<double> reference;
  int steps = 0;        // smallest N meeting the target
  double median = 0.0;  // its median relative error
};

double median_error(const Fig4& f, int steps) {
  pb::Settings s;
  s.steps = steps;
  std::vector<double> err;
  for (std::size_t i = 0; i < f.systems.size(); ++i)
    err.push_back(std::abs(pb::moreau_jean::solve(f.systems[i], s).pi1 - f.reference[i]) / f.reference[i]);
  std::nth_element(err.begin(), err.begin() + static_cast<long>(err.size() / 2), err.end());
  return err[err.size() / 2];
}

// The Fig. 4 family (kit/benchmarking.hpp); its reference and N are computed once.
const Fig4& fig4() {
  static const Fig4 f = [] {
    Fig4 out;
    out.systems = pb::bench::fig4_family();
    for (const pb::System& sys : out.systems) out.reference.push_back(pb::event_driven::solve(sys, {}).pi1);
    for (out.steps = 16; out.steps <= 65536; out.steps *= 2) {
      out.median = median_error(out, out.steps);
      if (out.median <= 1e-3) break;
    }
    return out;
  }();
  return f;
}

void BM_Fig4MoreauJeanToMedianError1e3(benchmark::State& state) {
  const Fig4& f = fig4();
  pb::Settings s = pb::bench::timed({});
  s.steps = f.steps;
  for (auto _ : state)
    for (const pb::System& sys : f.systems) benchmark::DoNotOptimize(pb::moreau_jean::solve(sys, s).pi1);
  state.counters["steps_N"] = f.steps;
  state.counters["median_error"] = f.median;
  state.counters["points"] = static_cast<double>(f.systems.size());
}
BENCHMARK(BM_Fig4MoreauJeanToMedianError1e3)->Unit(benchmark::kMillisecond);

void BM_Fig4ReferenceSamePoints(benchmark::State& state) {
  const Fig4& f = fig4();
  for (auto _ : state)
    for (const pb::System& sys : f.systems) benchmark::DoNotOptimize(pb::event_driven::solve(sys, {}).pi1);
  state.counters["points"] = static_cast<double>(f.systems.size());
}
BENCHMARK(BM_Fig4ReferenceSamePoints)->Unit(benchmark::kMillisecond);

}  // namespace
