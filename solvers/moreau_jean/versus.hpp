#pragma once
// The engines' benchmarks against the in-house Moreau-Jean: each engine's *_bench.cpp times
// its variants and, right after on the same case and N, moreau_jean::solve, so that their
// ratio (x_moreau_jean) compares the two under the same machine load.

#include <benchmark/benchmark.h>

#include <initializer_list>
#include <string>

#include "kit/benchmarking.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"

namespace pb::bench {

// time_variant at N = state.range(0), and x_moreau_jean: the CPU time of a run over
// moreau_jean::solve's on the same case and N. Returns the CPU time of time_variant's loop.
inline double time_vs_moreau_jean(benchmark::State& state, SolveFn solve, const char* variant, Scene scene) {
  const int steps = static_cast<int>(state.range(0));
  const double start = thread_seconds();
  time_variant(state, solve, variant, scene, steps);
  const double own = thread_seconds() - start;
  Settings in_house;
  in_house.steps = steps;
  state.counters["x_moreau_jean"] = ratio_to(seconds_per_run(&moreau_jean::solve, fig4_point(scene), in_house, own));
  return own;
}

// A variant of an engine, and what its benchmark names call it.
struct Labelled {
  const char* label;
  const char* variant;
};

// Registers, at_each_n (N = 64 and 256, or the steps given), <prefix>/<label>_<scene> for
// every variant on wall, pair and row3 (time_vs_moreau_jean), then
// <prefix>BaselineMoreauJean/<scene>: the baseline on its own. Returns true, to initialise a
// namespace-scope flag with.
inline bool register_vs_moreau_jean(const std::string& prefix, SolveFn solve,
                                    std::initializer_list<Labelled> variants,
                                    std::initializer_list<int> steps = {64, 256}) {
  const auto add = [steps](const std::string& title, auto fn) {
    at_each_n(benchmark::RegisterBenchmark(title.c_str(), fn), steps);
  };
  constexpr Scene kScenes[] = {Scene::wall, Scene::pair, Scene::row3};
  for (const Labelled& v : variants)
    for (Scene scene : kScenes)
      add(prefix + "/" + v.label + "_" + std::string(name(scene)),
          [solve, v, scene](benchmark::State& state) { time_vs_moreau_jean(state, solve, v.variant, scene); });
  for (Scene scene : kScenes)
    add(prefix + "BaselineMoreauJean/" + std::string(name(scene)),
        [scene](benchmark::State& state) { time_solve(state, &moreau_jean::solve, scene); });
  return true;
}

}  // namespace pb::bench
