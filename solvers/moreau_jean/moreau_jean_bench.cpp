// Cost per step of the Moreau-Jean stepper (targets: <= 20 ns/step for pair, <= 40 ns/step
// for row3, one core). Counters: time_per_step (CPU seconds per step) and steps per run.
// Run with --benchmark_repetitions=9 (or more) and read the medians.
//
// StepLoop times a step loop alone (the scheme is built before the timed loop and the
// start state restored between runs, outside the timing): the fixed-size loop of
// stepper.hpp on pair and row3, without and with the StepMonitor (/monitor:1), the same
// scenes on the any-size loop of dynamic.hpp (StepLoopDynamic), and the any-size loop on
// chains of 2 to 100 bodies (ChainStepLoop, the scaling with N; ChainStepLoopTouching: no
// gap, so that long runs of contacts push at every step). Solve times the public
// entry point, set-up included, as the sweeps time it (bench::timed: the monitor off).
// RunLcp times one Newton LCP of a run of L closed contacts, by TridiagonalLcp and by Lemke.

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <random>
#include <vector>

#include "kit/benchmarking.hpp"
#include "cases/system.hpp"
#include "kit/lcp/lemke.hpp"
#include "kit/monitor.hpp"
#include "solvers/moreau_jean/dynamic.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "solvers/moreau_jean/stepper.hpp"
#include "solvers/moreau_jean/tridiagonal_lcp.hpp"

namespace {

namespace mj = pb::moreau_jean;

// N = 1024 steps per shortest period makes a run long enough (~8k steps) that
// PauseTiming's own cost is negligible.
constexpr int kStepsPerPeriod = 1024;

// A chain under the pulse: alternating masses and frequencies (odd bodies half the mass
// and twice the frequency of body 0), gap Pi3 = 0.5 (or pi3), eps = 0.5, the Fig. 4 pulse.
pb::System chain_point(int bodies, double pi3 = 0.5) {
  pb::Case c = pb::bench::fig4_case(pb::Scene::chain);
  c.bodies = bodies;
  c.pi3 = pi3;
  c.pi6 = 2.0;
  return pb::make_system(c);
}

template <int NB, int NC>
void step_loop(benchmark::State& state, pb::Scene scene) {
  const pb::System s = pb::bench::fig4_point(scene);
  const bool monitored = state.range(0) != 0;
  const double h = s.step(kStepsPerPeriod);
  const long steps = pb::step_count(s.t_end, h);
  const auto scheme = mj::make_scheme<NB, NC>(s, h, 0.5, 0.5);
  using VecB = typename mj::Scheme<NB, NC>::VecB;
  const auto start = mj::make_state(scheme, VecB::Zero().eval(), VecB::Zero().eval());
  mj::Tally tally;
  for (auto _ : state) {
    state.PauseTiming();
    auto st = start;
    tally = {};
    mj::FixedStepMonitor<NB, NC> monitor(s, h);
    state.ResumeTiming();
    const bool ok = monitored ? mj::advance<NB, NC, false, true>(scheme, st, tally, steps, nullptr, &monitor)
                              : mj::advance<NB, NC, false, false>(scheme, st, tally, steps, nullptr);
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(tally.u_max);
  }
  state.counters["time_per_step"] = pb::bench::per_step(steps);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["impacts"] = static_cast<double>(tally.impacts);
}

void BM_MoreauJeanStepLoopPair(benchmark::State& state) { step_loop<2, 1>(state, pb::Scene::pair); }
void BM_MoreauJeanStepLoopRow3(benchmark::State& state) { step_loop<3, 2>(state, pb::Scene::row3); }
BENCHMARK(BM_MoreauJeanStepLoopPair)->ArgName("monitor")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MoreauJeanStepLoopRow3)->ArgName("monitor")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The any-size loop on system s; counters as above, plus tridiagonal solves per step.
void dynamic_loop(benchmark::State& state, const pb::System& s, bool monitored) {
  const double h = s.step(kStepsPerPeriod);
  const long steps = pb::step_count(s.t_end, h);
  const mj::dynamic::Scheme scheme = mj::dynamic::make_scheme(s, h, 0.5, 0.5);
  const mj::dynamic::State start = mj::dynamic::make_state(scheme, s.u_start.data(), s.v_start.data());
  mj::dynamic::Work work = mj::dynamic::make_work(scheme);
  mj::Tally tally;
  long passes = 0;
  for (auto _ : state) {
    state.PauseTiming();
    mj::dynamic::State st = start;
    tally = {};
    work.lcp_passes = 0;
    pb::StepMonitor monitor(s);
    state.ResumeTiming();
    const bool ok = mj::dynamic::advance(scheme, st, work, tally, steps, nullptr, monitored ? &monitor : nullptr);
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(tally.u_max);
    passes = work.lcp_passes;
  }
  state.counters["time_per_step"] = pb::bench::per_step(steps);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["impacts"] = static_cast<double>(tally.impacts);
  state.counters["lcp_passes_per_step"] = static_cast<double>(passes) / static_cast<double>(steps);
}

void BM_MoreauJeanStepLoopDynamic(benchmark::State& state) {
  dynamic_loop(state, pb::bench::fig4_point(state.range(0) == 2 ? pb::Scene::pair : pb::Scene::row3), false);
}
BENCHMARK(BM_MoreauJeanStepLoopDynamic)->ArgName("bodies")->Arg(2)->Arg(3)->Unit(benchmark::kMicrosecond);

void BM_MoreauJeanChainStepLoop(benchmark::State& state) {
  dynamic_loop(state, chain_point(static_cast<int>(state.range(0))), state.range(1) != 0);
}
BENCHMARK(BM_MoreauJeanChainStepLoop)
    ->ArgNames({"bodies", "monitor"})
    ->ArgsProduct({{2, 5, 10, 20, 50, 100}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

// The same chains touching at rest (Pi3 = 0): long runs of closed contacts, solved by
// TridiagonalLcp at every step.
void BM_MoreauJeanChainStepLoopTouching(benchmark::State& state) {
  dynamic_loop(state, chain_point(static_cast<int>(state.range(0)), 0.0), false);
}
BENCHMARK(BM_MoreauJeanChainStepLoopTouching)->ArgName("bodies")->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);

void solve(benchmark::State& state, pb::Scene scene) {
  pb::bench::time_solve(state, &pb::moreau_jean::solve, scene);
}

void BM_MoreauJeanSolvePair(benchmark::State& state) { solve(state, pb::Scene::pair); }
void BM_MoreauJeanSolveRow3(benchmark::State& state) { solve(state, pb::Scene::row3); }
BENCHMARK(BM_MoreauJeanSolvePair)->ArgName("N")->Arg(64)->Arg(1024)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MoreauJeanSolveRow3)->ArgName("N")->Arg(64)->Arg(1024)->Unit(benchmark::kMicrosecond);

// The public entry point on a chain at the default N = 64 (monitor off, bench::timed): chains of 2 and 3
// take the fixed-size loop, longer ones the any-size loop.
void BM_MoreauJeanSolveChain(benchmark::State& state) {
  const pb::System s = chain_point(static_cast<int>(state.range(0)));
  long steps = 0;
  for (auto _ : state) {
    const pb::Result r = mj::solve(s, pb::bench::timed({}));
    steps = r.steps;
    benchmark::DoNotOptimize(r.pi1);
  }
  state.counters["time_per_step"] = pb::bench::per_step(steps);
  state.counters["steps"] = static_cast<double>(steps);
}
BENCHMARK(BM_MoreauJeanSolveChain)->ArgName("bodies")->Arg(2)->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Arg(100)
    ->Unit(benchmark::kMicrosecond);

// One LCP of a run of L closed contacts between bodies of alternating masses 1 and 0.5
// (M_hat = M): a cradle (one contact approaching, the rest at rest: the impulse travels
// the whole run, L passes of a cold start) or a random right-hand side in [-1, 1].
struct RunLcp {
  Eigen::VectorXd d, o, q;
  Eigen::MatrixXd a;
  RunLcp(int n, bool cradle) : d(n), o(n), q(n), a(Eigen::MatrixXd::Zero(n, n)) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto minv = [](int body) { return body % 2 == 0 ? 1.0 : 2.0; };
    for (int i = 0; i < n; ++i) {
      d(i) = a(i, i) = minv(i) + minv(i + 1);
      o(i) = -minv(i + 1);
      if (i + 1 < n) a(i, i + 1) = a(i + 1, i) = o(i);
      q(i) = cradle ? (i == 0 ? -1.0 : 0.0) : unit(rng);
    }
  }
};

void BM_MoreauJeanRunLcpTridiagonal(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const RunLcp p(n, state.range(1) != 0);
  mj::TridiagonalLcp solver;
  solver.reserve(n);
  Eigen::VectorXd z(n);
  int passes = 0;
  for (auto _ : state) {
    passes = solver.solve(p.d.data(), p.o.data(), p.q.data(), z.data(), n, nullptr);
    benchmark::DoNotOptimize(z.data());
  }
  state.counters["passes"] = passes;
}

void BM_MoreauJeanRunLcpLemke(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const RunLcp p(n, state.range(1) != 0);
  pb::lcp::LemkeWorkspace ws;
  ws.reserve(n, 1);
  Eigen::VectorXd z(n);
  int pivots = 0;
  for (auto _ : state) {
    pivots = pb::lcp::lemke(p.a, p.q, z, ws).pivots;
    benchmark::DoNotOptimize(z.data());
  }
  state.counters["pivots"] = pivots;
}
BENCHMARK(BM_MoreauJeanRunLcpTridiagonal)
    ->ArgNames({"L", "cradle"})
    ->ArgsProduct({{3, 10, 30, 100}, {0, 1}});
BENCHMARK(BM_MoreauJeanRunLcpLemke)->ArgNames({"L", "cradle"})->ArgsProduct({{3, 10, 30, 100}, {0, 1}});

}  // namespace
