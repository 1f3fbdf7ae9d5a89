#pragma once
// What the benchmarks share: the cases they time, the per-step counter, and the timing of an
// engine against an in-house solver on the same case (the engine benchmarks: ODE, Bullet,
// Siconos).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <initializer_list>
#include <string>
#include <vector>

#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb::bench {

// A Fig. 4 case (Pi2 = 1, Pi3 = 0.5, Pi5 = 0.5, Pi6 = 1, eps = 0.5, cosine, normal) with
// impacts in every scene; row3 is the symmetric configuration of Fig. 7.
inline Case fig4_case(Scene scene) {
  Case c;
  c.scene = scene;
  c.pulse = PulseShape::cosine;
  c.pi2 = 1.0;
  c.pi3 = 0.5;
  c.pi5 = 0.5;
  c.pi6 = 1.0;
  c.pi7 = 0.5;
  c.pi8 = 1.0;
  c.eps = 0.5;
  return c;
}

inline System fig4_point(Scene scene) { return make_system(fig4_case(scene)); }

// The one timing rule of the benchmarks, the sweeps' (sweep/sweep.hpp): the solve alone, with
// Settings::monitor off, on the thread's CPU clock, the clock read around many runs rather than
// after each. The ratios' Moreau-Jean baseline was timed with the monitor on and the clock read
// after every run: 1.82 / 3.24 / 5.46 us per run on wall / pair / row3 against 1.17 / 2.12 /
// 3.24 us unmonitored (issue 36), which understated every engine's ratio 1.5-1.7 times.
inline Settings timed(Settings settings) {
  settings.monitor = false;
  return settings;
}

// The repetitions of a benchmark that times a whole set or a growth (seconds a repetition): three
// give the main job their median. POUNDBENCH_BENCH_REPETITIONS sets another count, for the tests
// that run every benchmark to see that it runs (bench_smoke: one; report_smoke: two, the fewest
// whose median the report reads), not to measure it.
inline int whole_set_repetitions() {
  const char* text = std::getenv("POUNDBENCH_BENCH_REPETITIONS");
  const int n = text ? std::atoi(text) : 0;
  return n >= 1 ? n : 3;
}

// CPU seconds per step (the console prints it with an SI prefix: "7.5n" is 7.5 ns).
inline benchmark::Counter per_step(long steps) {
  return benchmark::Counter(static_cast<double>(steps),
                            benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// Times `solve` on fig4_point(scene) with N = state.range(0) steps per shortest period;
// counters: time_per_step and steps per run.
inline void time_solve(benchmark::State& state, SolveFn solve, Scene scene) {
  const System s = fig4_point(scene);
  Settings settings = timed({});
  settings.steps = static_cast<int>(state.range(0));
  long steps = 0;
  for (auto _ : state) {
    const Result r = solve(s, settings);
    steps = r.steps;
    benchmark::DoNotOptimize(r.pi1);
  }
  state.counters["time_per_step"] = per_step(steps);
  state.counters["steps"] = static_cast<double>(steps);
}

// The Fig. 4 pair family: normal directivity, both pulses, the paper's eight Pi5, Pi6 = 1,
// Pi3 = 0.5, eps = 0.5, 50 log-spaced Pi2 in [0.1, 10].
inline std::vector<System> fig4_family() {
  std::vector<System> systems;
  for (PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
    for (double pi5 : {0.1, 0.25, 0.5, 0.75, 1.33, 2.0, 4.0, 10.0}) {
      for (int k = 0; k < 50; ++k) {
        Case c = fig4_case(Scene::pair);
        c.pulse = p;
        c.pi5 = pi5;
        c.pi2 = 0.1 * std::pow(100.0, k / 49.0);
        systems.push_back(make_system(c));
      }
    }
  }
  return systems;
}

// CPU seconds of this thread: what the benchmark library divides rate counters by, and what a
// loaded machine disturbs less than wall time.
inline double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// CPU seconds per run of solve(s, timed(settings)), over at least `seconds` of CPU time (20 ms
// at most): the baseline of a ratio, measured right after the timed loop so that both see the
// same machine load, for as long as that loop ran (its CPU time, passed as `seconds`). The
// library calls a benchmark function a few times to size its loop, then once per repetition:
// a fixed 20 ms baseline on every call was most of the engines' benchmarks' time. The clock is
// read once per batch, the batches doubling, so its 0.37 us a reading is spread over them.
inline double seconds_per_run(SolveFn solve, const System& s, const Settings& settings, double seconds = 0.02) {
  const Settings unmonitored = timed(settings);
  long runs = 0;
  const double start = thread_seconds();
  double elapsed = 0.0;
  for (long batch = 1; elapsed < std::min(seconds, 0.02); batch *= 2) {
    for (long k = 0; k < batch; ++k) {
      const Result r = solve(s, unmonitored);
      benchmark::DoNotOptimize(r.pi1);
    }
    runs += batch;
    elapsed = thread_seconds() - start;
  }
  return elapsed / static_cast<double>(runs);
}

// A run's CPU time over `baseline_seconds`, as a counter: an inverted rate of the baseline's
// seconds per run (the console prints it with an "s"; read it as a plain ratio).
inline benchmark::Counter ratio_to(double baseline_seconds) {
  return benchmark::Counter(baseline_seconds,
                            benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// The counters of a timed run: time_per_step, steps, impacts; an error if it did not end ok.
inline void report(benchmark::State& state, const Result& r) {
  if (r.status != Status::ok) state.SkipWithError(r.message.c_str());
  state.counters["time_per_step"] = per_step(r.steps);
  state.counters["steps"] = static_cast<double>(r.steps);
  state.counters["impacts"] = static_cast<double>(r.impacts);
}

// The chain of the engine benchmarks: n bodies alternating (odd bodies Pi5 = 0.5, Pi6 = 1)
// with a gap (Pi3 = 0.5) under the cosine pulse (Pi2 = 1, eps = 0.5): the Fig. 4 case's.
inline System chain_point(int bodies) {
  Case c = fig4_case(Scene::chain);
  c.bodies = bodies;
  return make_system(c);
}

// Times `solve` with default settings on chain_point(state.range(0)): the counters of
// report() and time_per_body_step. Returns the last result.
inline Result time_chain(benchmark::State& state, SolveFn solve) {
  const int bodies = static_cast<int>(state.range(0));
  const System s = chain_point(bodies);
  Result r;
  for (auto _ : state) {
    r = solve(s, timed({}));
    benchmark::DoNotOptimize(r.pi1);
  }
  report(state, r);
  state.counters["time_per_body_step"] = per_step(r.steps * bodies);
  return r;
}

// Times `solve` with `variant` and N = `steps` (0: none) on fig4_point(scene): the counters
// of report(). Returns the last result.
inline Result time_variant(benchmark::State& state, SolveFn solve, const char* variant, Scene scene, int steps) {
  const System s = fig4_point(scene);
  Settings settings = timed({});
  settings.variant = variant;
  settings.steps = steps;
  Result r;
  for (auto _ : state) {
    r = solve(s, settings);
    benchmark::DoNotOptimize(r.pi1);
  }
  report(state, r);
  return r;
}

// The step counts of the per-case benchmarks: N = 64 and 256 (or those given), timed in
// microseconds.
inline benchmark::internal::Benchmark* at_each_n(benchmark::internal::Benchmark* b,
                                                 std::initializer_list<int> steps = {64, 256}) {
  b->ArgName("N")->Unit(benchmark::kMicrosecond);
  for (int n : steps) b->Arg(n);
  return b;
}

}  // namespace pb::bench
