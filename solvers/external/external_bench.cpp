// The external solver's cost per point (docs/external.md, "What a point costs"): the same
// case solved in process, through `poundbench adapter` (poundbench as its own external
// program: the same moreau-jean solve plus the protocol and poundbench's start), and by a
// program that does nothing but answer (`cat` of a stored answer: the protocol's floor, a
// spawn, the pipes, the two documents and the wait). Wall time: the work is in a child.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "kit/benchmarking.hpp"
#include "solvers/external/external.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"

namespace pb::bench {
namespace {

void time_external(benchmark::State& state, const std::string& command) {
  const System s = fig4_point(Scene::pair);
  Settings settings;
  settings.steps = 64;
  settings.command = command;
  for (auto _ : state) {
    const Result r = external::solve(s, settings);
    if (r.status != Status::ok) state.SkipWithError(r.message.c_str());
    benchmark::DoNotOptimize(r.pi1);
  }
}

void BM_ExternalPairInProcess(benchmark::State& state) {
  const System s = fig4_point(Scene::pair);
  Settings settings;
  settings.steps = 64;
  for (auto _ : state) benchmark::DoNotOptimize(moreau_jean::solve(s, settings).pi1);
}
BENCHMARK(BM_ExternalPairInProcess)->UseRealTime()->Unit(benchmark::kMicrosecond);

void BM_ExternalPairThroughAdapter(benchmark::State& state) {
  time_external(state, POUNDBENCH_EXE " adapter --solver moreau-jean");
}
BENCHMARK(BM_ExternalPairThroughAdapter)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_ExternalProtocolFloor(benchmark::State& state) {
  const std::string answer = "/tmp/poundbench-bench-answer.json";
  std::ofstream(answer) << R"({"version":1,"status":"ok","pi1":1})" << '\n';
  time_external(state, "cat " + answer);
  std::remove(answer.c_str());
}
BENCHMARK(BM_ExternalProtocolFloor)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace pb::bench
