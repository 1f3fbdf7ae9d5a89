#pragma once
// What the benchmarks share: the cases they time and the per-step counter.

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "cases/system.hpp"
#include "solvers/solver.hpp"

namespace pb::bench {

// A Fig. 4 point (Pi2 = 1, Pi3 = 0.5, Pi5 = 0.5, Pi6 = 1, eps = 0.5, cosine, normal) with
// impacts in every scene; row3 is the symmetric configuration of Fig. 7.
inline System fig4_point(Scene scene) {
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
  return make_system(c);
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
  Settings settings;
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
        Case c;
        c.scene = Scene::pair;
        c.pulse = p;
        c.pi3 = 0.5;
        c.pi5 = pi5;
        c.pi6 = 1.0;
        c.eps = 0.5;
        c.pi2 = 0.1 * std::pow(100.0, k / 49.0);
        systems.push_back(make_system(c));
      }
    }
  }
  return systems;
}

}  // namespace pb::bench
