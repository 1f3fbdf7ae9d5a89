// Cost per step of the Moreau-Jean stepper (targets: <= 20 ns/step for pair, <= 40 ns/step
// for row3, one core). Counters: time_per_step (CPU seconds per step) and steps per run.
// Run with --benchmark_repetitions=9 (or more) and read the medians.
//
// StepLoop times the step loop alone (stepper.hpp advance(): the scheme is built before
// the timed loop and the start state restored between runs, outside the timing);
// Solve times the public entry point, set-up included, at the default N = 64 and at 1024.

#include <benchmark/benchmark.h>

#include "bench/support.hpp"
#include "cases/system.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "solvers/moreau_jean/stepper.hpp"

namespace {

template <int NB, int NC>
void step_loop(benchmark::State& state, pb::Scene scene) {
  namespace mj = pb::moreau_jean;
  const pb::System s = pb::bench::fig4_point(scene);
  const int n_per_period = static_cast<int>(state.range(0));
  const double h = s.step(n_per_period);
  const long steps = mj::step_count(s.t_end, h);
  const auto scheme = mj::make_scheme<NB, NC>(s, h, 0.5, 0.5);
  using VecB = typename mj::Scheme<NB, NC>::VecB;
  const auto start = mj::make_state(scheme, VecB::Zero().eval(), VecB::Zero().eval());
  mj::Tally tally;
  for (auto _ : state) {
    state.PauseTiming();
    auto st = start;
    tally = {};
    state.ResumeTiming();
    const bool ok = mj::advance<NB, NC, false>(scheme, st, tally, steps, nullptr);
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(tally.u_max);
  }
  state.counters["time_per_step"] = pb::bench::per_step(steps);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["impacts"] = static_cast<double>(tally.impacts);
}

void BM_MoreauJeanStepLoopPair(benchmark::State& state) { step_loop<2, 1>(state, pb::Scene::pair); }
void BM_MoreauJeanStepLoopRow3(benchmark::State& state) { step_loop<3, 2>(state, pb::Scene::row3); }
// N = 1024 makes a run long enough (~13k steps) that PauseTiming's own cost is negligible.
BENCHMARK(BM_MoreauJeanStepLoopPair)->ArgName("N")->Arg(1024)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MoreauJeanStepLoopRow3)->ArgName("N")->Arg(1024)->Unit(benchmark::kMicrosecond);

void solve(benchmark::State& state, pb::Scene scene) {
  pb::bench::time_solve(state, &pb::moreau_jean::solve, scene);
}

void BM_MoreauJeanSolvePair(benchmark::State& state) { solve(state, pb::Scene::pair); }
void BM_MoreauJeanSolveRow3(benchmark::State& state) { solve(state, pb::Scene::row3); }
BENCHMARK(BM_MoreauJeanSolvePair)->ArgName("N")->Arg(64)->Arg(1024)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MoreauJeanSolveRow3)->ArgName("N")->Arg(64)->Arg(1024)->Unit(benchmark::kMicrosecond);

}  // namespace
