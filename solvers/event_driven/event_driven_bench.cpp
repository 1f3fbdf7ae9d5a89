// Cost of one reference solve. Inputs are built outside the timed loop.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "kit/benchmarking.hpp"
#include "cases/system.hpp"
#include "solvers/event_driven/event_driven.hpp"

namespace {

// The reference on one system, timed; its impacts as a counter.
void time_reference(benchmark::State& state, const pb::System& s) {
  long impacts = 0;
  for (auto _ : state) {
    const pb::Result r = pb::event_driven::solve(s, {});
    impacts = r.impacts;
    benchmark::DoNotOptimize(r.pi1);
  }
  state.counters["impacts"] = static_cast<double>(impacts);
}

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
  time_reference(state, pb::make_system(c));
}
BENCHMARK(BM_EventDrivenPairFig4)
    ->ArgNames({"pi5x100", "pi2x100"})
    ->ArgsProduct({{25, 75, 133, 400}, {30, 100, 300}})
    ->Unit(benchmark::kMicrosecond);

// Issue 32's case (pair, sine, normal, Pi3 = 0.5, eps = 0.5, Pi5 = 4, Pi6 = 1, xi = 0) at
// Pi2 = 4 - 5e-5, 4 and 4 + 5e-5: body 1 resonant with the pulse and body 0, undamped, at
// four times its frequency, whose wave rounds to exact zeros near t = 0 (search.cpp,
// max_abs). The three should cost alike (53 impacts each); Pi2 = 4 took 40 times as long.
void BM_EventDrivenPowerOfTwoPi2(benchmark::State& state) {
  pb::Case c;
  c.scene = pb::Scene::pair;
  c.pulse = pb::PulseShape::sine;
  c.pi2 = 4.0 + 5e-5 * static_cast<double>(state.range(0));
  c.pi3 = 0.5;
  c.eps = 0.5;
  c.pi5 = 4.0;
  c.pi6 = 1.0;
  c.xi = 0.0;
  time_reference(state, pb::make_system(c));
}
BENCHMARK(BM_EventDrivenPowerOfTwoPi2)->ArgName("pi2_minus_4_in_5e-5")->DenseRange(-1, 1)->Unit(benchmark::kMicrosecond);

}  // namespace

namespace {

// The whole Fig. 4 pair family (kit/benchmarking.hpp): each point is timed on its own, and
// the median and 90th percentile per point are reported (the target is a median <= 50 us).
void BM_EventDrivenFig4FamilyPerPoint(benchmark::State& state) {
  const std::vector<pb::System> systems = pb::bench::fig4_family();
  std::vector<double> seconds(systems.size(), 0.0);
  for (auto _ : state) {
    for (std::size_t i = 0; i < systems.size(); ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const pb::Result r = pb::event_driven::solve(systems[i], {});
      benchmark::DoNotOptimize(r.pi1);
      seconds[i] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
  }
  std::vector<double> per_point = seconds;
  for (double& s : per_point) s /= static_cast<double>(state.iterations());
  std::sort(per_point.begin(), per_point.end());
  state.counters["median_us"] = 1e6 * per_point[per_point.size() / 2];
  state.counters["p90_us"] = 1e6 * per_point[per_point.size() * 9 / 10];
  state.counters["max_us"] = 1e6 * per_point.back();
  state.counters["points"] = static_cast<double>(systems.size());
}
BENCHMARK(BM_EventDrivenFig4FamilyPerPoint)->Unit(benchmark::kMillisecond);

}  // namespace

namespace {

// A chain of n bodies, odd ones with Pi5 = 2 and Pi6 = 0.5, gaps pi3, restitution eps, under
// the sine pulse at Pi2 = 1, body 0 kicked at kick a_p / w_p.
pb::Case alternating_chain(std::int64_t n, double kick, double pi3, double eps) {
  pb::Case c;
  c.scene = pb::Scene::chain;
  c.bodies = static_cast<int>(n);
  c.kick = kick;
  c.pulse = pb::PulseShape::sine;
  c.pi2 = 1.0;
  c.pi3 = pi3;
  c.pi5 = 2.0;
  c.pi6 = 0.5;
  c.eps = eps;
  return c;
}

// Cost of one reference run of the N-body chain against N: alternating bodies (odd ones
// with Pi5 = 2, Pi6 = 0.5), a gap (Pi3 = 0.5), eps = 0.5, sine pulse, Pi2 = 1. Without a
// kick even and odd bodies move alike and impacts come in simultaneous rows; a kick of
// a_p / w_p on body 0 breaks that symmetry. Counters: events and impacts per run, the time
// per event and per impact, and impacts per event: here an event is a row of simultaneous
// impacts that grows with N (about N / 6 of them), so the time per event grows with N even
// where the time per impact does not. full_search:1 searches every contact at every event
// (event_driven::detail), as before a contact kept its last search's answer while no event
// moved its bodies: the two side by side, in one run.
void BM_EventDrivenChain(benchmark::State& state) {
  const pb::Case c = alternating_chain(state.range(0), static_cast<double>(state.range(1)), 0.5, 0.5);
  const pb::System s = pb::make_system(c);
  const auto solve = state.range(2) ? pb::event_driven::detail::solve_searching_every_contact : pb::event_driven::solve;
  long events = 0, impacts = 0;
  for (auto _ : state) {
    const pb::Result r = solve(s, {});
    events = r.steps;
    impacts = r.impacts;
    benchmark::DoNotOptimize(r.pi1);
  }
  state.counters["events"] = static_cast<double>(events);
  state.counters["impacts"] = static_cast<double>(impacts);
  state.counters["time_per_event"] = pb::bench::per_step(events);
  state.counters["time_per_impact"] = pb::bench::per_step(impacts);
  state.counters["impacts_per_event"] = events > 0 ? static_cast<double>(impacts) / static_cast<double>(events) : 0.0;
}
BENCHMARK(BM_EventDrivenChain)
    ->ArgNames({"N", "kick", "full_search"})
    ->ArgsProduct({{2, 5, 10, 20, 50, 100}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

}  // namespace

namespace {

// A touching chain (issue 36): the stress set's Newton's cradle (cases/sets/stress.toml,
// family cradle: N equal bodies at rest in contact, Pi3 = 0, eps = 1, body 0 kicked at
// a_p / w_p) at its costliest point, sine pulse and Pi2 = 0.1, and the alternating chain
// touching at rest (Pi5 = 2, Pi6 = 0.5, the same kick and eps), whose events are mostly
// one contact's impact. eager:1 advances every body and rebuilds the whole frame at every
// event (event_driven::detail), as the reference did before its events rebuilt only the
// clusters they change: the two side by side, in one run.
void BM_EventDrivenTouchingChain(benchmark::State& state) {
  pb::Case c = alternating_chain(state.range(0), 1.0, 0.0, 1.0);
  if (!state.range(1)) {  // the cradle
    c.pi2 = 0.1;
    c.pi5 = 1.0;
    c.pi6 = 1.0;
  }
  const pb::System s = pb::make_system(c);
  const auto solve = state.range(2) ? pb::event_driven::detail::solve_rebuilding_every_body : pb::event_driven::solve;
  long events = 0;
  for (auto _ : state) {
    const pb::Result r = solve(s, {});
    events = r.steps;
    benchmark::DoNotOptimize(r.pi1);
  }
  state.counters["events"] = static_cast<double>(events);
  state.counters["time_per_event"] = pb::bench::per_step(events);
}
BENCHMARK(BM_EventDrivenTouchingChain)
    ->ArgNames({"N", "alternating", "eager"})
    ->ArgsProduct({{100, 300, 1000}, {0}, {0, 1}})
    // The alternating chain lazily at N = 100, 300 and 1000 (0.35 s a run since an open gap's
    // far cluster is no longer rebuilt whole), eagerly at 100 only: eagerly at 300 it took 8 s
    // of the main job's benchmarks (and at N = 1000, 55 s a run: DERIVATION.md §9).
    ->ArgsProduct({{100, 300, 1000}, {1}, {0}})
    ->Args({100, 1, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace

namespace {

// What a touching chain's run costs at 1000 bodies against 100 (issue 46: at most 30 times,
// for 7.7 times the events): the touching alternating chain of BM_EventDrivenTouchingChain,
// CPU time of the thread, the two sizes alternated in each iteration (and which goes first),
// so that both see the same load; counter growth, the ratio of their sums. One iteration is
// two runs of each (about 1 s); three repetitions whatever --benchmark_repetitions says.
void BM_EventDrivenTouchingChainGrowth(benchmark::State& state) {
  const pb::System small = pb::make_system(alternating_chain(100, 1.0, 0.0, 1.0));
  const pb::System large = pb::make_system(alternating_chain(1000, 1.0, 0.0, 1.0));
  double seconds[2] = {};
  const auto run = [&](int which) {
    const double start = pb::bench::thread_seconds();
    benchmark::DoNotOptimize(pb::event_driven::solve(which ? large : small, {}).pi1);
    seconds[which] += pb::bench::thread_seconds() - start;
  };
  for (auto _ : state) {
    for (const int first : {0, 1}) {
      run(first);
      run(1 - first);
    }
  }
  state.counters["growth"] = seconds[1] / seconds[0];
}
BENCHMARK(BM_EventDrivenTouchingChainGrowth)->Iterations(1)->Repetitions(pb::bench::whole_set_repetitions())->Unit(benchmark::kMillisecond);

}  // namespace
