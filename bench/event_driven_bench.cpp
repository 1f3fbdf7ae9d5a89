// Cost of one reference solve. Inputs are built outside the timed loop.

#include <benchmark/benchmark.h>

#include "cases/system.hpp"
#include "solvers/event_driven/event_driven.hpp"

namespace {

// One pair point of the Fig. 4 family (Pi3 = 0.5, Pi6 = 1, eps = 0.5) per Pi5, Pi2.
void BM_EventDrivenPairFig4(benchmark::State& state) {
  pb::Case c;
  c.scene = pb::Scene::pair;
  c.pulse = pb::PulseShape::cosine;
  c.pi3 = 0.5;
  c.pi6 = 1.0;
  c.eps = 0.5;
  c.pi5 = static_cast<double>(state.range(0)) / 100.0;
  c.pi2 = static_cast<double>(state.range(1)) / 100.0;
  const pb::System s = pb::make_system(c);
  long impacts = 0;
  for (auto _ : state) {
    const pb::Result r = pb::event_driven::solve(s, {});
    impacts = r.impacts;
    benchmark::DoNotOptimize(r.pi1);
  }
  state.counters["impacts"] = static_cast<double>(impacts);
}
BENCHMARK(BM_EventDrivenPairFig4)
    ->ArgNames({"pi5x100", "pi2x100"})
    ->ArgsProduct({{25, 75, 133, 400}, {30, 100, 300}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
