// Throughput of whole spectra through the sweep runner, on 1 and on 2 threads, in one run
// so that the ratio is measured under the same machine load.

#include <benchmark/benchmark.h>

#include <string>

#include "cases/case_set.hpp"
#include "solvers/solver.hpp"
#include "sweep/sweep.hpp"

namespace {

// The Fig. 4 families of the shipped paper set (3 200 points) through the reference.
void BM_SweepFig4Reference(benchmark::State& state) {
  const pb::CaseSet all = pb::load_case_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/paper.toml");
  std::vector<pb::Case> cases;
  for (const pb::Case& c : all.cases)
    if (c.family.rfind("fig4", 0) == 0) cases.push_back(c);
  const pb::SolverInfo& solver = *pb::find_solver("event-driven");
  pb::SweepOptions options;
  options.threads = static_cast<unsigned>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(pb::run_sweep(cases, solver, {}, options));
  state.counters["points_per_s"] =
      benchmark::Counter(static_cast<double>(cases.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_SweepFig4Reference)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
