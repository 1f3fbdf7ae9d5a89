// Cost of the LCP solvers of kit/lcp/ at the sizes the scenes produce: one and two
// contacts (small.hpp), and n = 2, 10, 100 for Lemke and PGS (the chain scene of a later
// issue has up to 100 contacts). Each benchmark cycles through a fixed set of seeded
// problems built before the timed loop, so no branch pattern is learnt from one input.

#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "kit/lcp/lemke.hpp"
#include "kit/lcp/pgs.hpp"
#include "kit/lcp/small.hpp"

namespace {

constexpr int kProblems = 16;

struct Problem {
  Eigen::MatrixXd a;
  Eigen::VectorXd q;
};

// family 0: W^T M^-1 W of a chain of n contacts (wall, then n bodies, masses over a
// decade), tridiagonal; family 1: dense SPD B B^T / n + I. q = w* - A z* with about half
// of the contacts closed (z* > 0) and half open (w* > 0).
std::vector<Problem> problems(int n, int family) {
  std::mt19937_64 rng(static_cast<unsigned long>(1000 * n + family));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  std::vector<Problem> out;
  for (int t = 0; t < kProblems; ++t) {
    Problem p;
    p.a = Eigen::MatrixXd::Zero(n, n);
    if (family == 0) {
      Eigen::VectorXd inv_m(n + 1);
      for (int i = 0; i <= n; ++i) inv_m(i) = std::exp(2.3 * (u(rng) - 0.5));
      inv_m(0) = 0.0;
      for (int j = 0; j < n; ++j) {
        p.a(j, j) = inv_m(j) + inv_m(j + 1);
        if (j + 1 < n) p.a(j, j + 1) = p.a(j + 1, j) = -inv_m(j + 1);
      }
    } else {
      Eigen::MatrixXd b(n, n);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) b(i, j) = g(rng);
      p.a = b * b.transpose() / n + Eigen::MatrixXd::Identity(n, n);
    }
    Eigen::VectorXd z = Eigen::VectorXd::Zero(n), w = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) (u(rng) < 0.5 ? z(i) : w(i)) = 0.1 + u(rng);
    p.q = w - p.a * z;
    out.push_back(std::move(p));
  }
  return out;
}

void BM_Solve1(benchmark::State& state) {
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g;
  std::vector<double> a(kProblems), q(kProblems);
  for (int t = 0; t < kProblems; ++t) a[t] = std::exp(g(rng)), q[t] = g(rng);
  int t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(pb::lcp::solve1(a[t], q[t]));
    t = (t + 1) % kProblems;
  }
}
BENCHMARK(BM_Solve1);

void BM_Solve2(benchmark::State& state) {
  // Three bodies in a row: [[1/m1 + 1/m0, -1/m0], [-1/m0, 1/m0 + 1/m2]].
  std::mt19937_64 rng(2);
  std::normal_distribution<double> g;
  std::vector<Eigen::Matrix2d> a(kProblems);
  std::vector<Eigen::Vector2d> q(kProblems);
  for (int t = 0; t < kProblems; ++t) {
    const double i0 = std::exp(g(rng)), i1 = std::exp(g(rng)), i2 = std::exp(g(rng));
    a[t] << i1 + i0, -i0, -i0, i0 + i2;
    q[t] << g(rng), g(rng);
  }
  int t = 0;
  for (auto _ : state) {
    Eigen::Vector2d z = pb::lcp::solve2(a[t], q[t]);
    benchmark::DoNotOptimize(z.data());
    t = (t + 1) % kProblems;
  }
}
BENCHMARK(BM_Solve2);

// Times `solve(problem, z)`, which returns its iterations and whether it solved, cycling through
// problems(n, family) with (n, family) = state.range(0), state.range(1); counters: the mean
// iterations per solve as `iterations`, and the solves that failed.
template <class Solve>
void time_cycle(benchmark::State& state, const char* iterations, Solve solve) {
  const int n = static_cast<int>(state.range(0));
  const std::vector<Problem> ps = problems(n, static_cast<int>(state.range(1)));
  Eigen::VectorXd z(n);
  long total = 0, solves = 0, failed = 0;
  int t = 0;
  for (auto _ : state) {
    const auto [count, solved] = solve(ps[t], z);
    benchmark::DoNotOptimize(z.data());
    total += count;
    failed += !solved;
    ++solves;
    t = (t + 1) % kProblems;
  }
  state.counters[iterations] = static_cast<double>(total) / static_cast<double>(solves);
  state.counters["failed"] = static_cast<double>(failed);
}

// n = 2, 10, 100 contacts of either family.
void sizes_and_families(benchmark::internal::Benchmark* b) {
  b->ArgNames({"n", "dense"})->ArgsProduct({{2, 10, 100}, {0, 1}})->Unit(benchmark::kMicrosecond);
}

void BM_Lemke(benchmark::State& state) {
  pb::lcp::LemkeWorkspace ws;
  time_cycle(state, "pivots", [&ws](const Problem& p, Eigen::VectorXd& z) {
    const pb::lcp::LemkeResult r = pb::lcp::lemke(p.a, p.q, z, ws);
    return std::pair{r.pivots, r.status == pb::lcp::Status::solved};
  });
}
BENCHMARK(BM_Lemke)->Apply(sizes_and_families);

// Cold start (z = 0), absolute residual tolerance 1e-10 on problems with |q| ~ 1.
pb::lcp::PgsSettings cold_start_settings() {
  pb::lcp::PgsSettings settings;
  settings.tol = 1e-10;
  settings.max_sweeps = 1000000;
  return settings;
}

void BM_Pgs(benchmark::State& state) {
  const pb::lcp::PgsSettings settings = cold_start_settings();
  time_cycle(state, "sweeps", [&settings](const Problem& p, Eigen::VectorXd& z) {
    z.setZero();
    const pb::lcp::PgsResult r = pb::lcp::pgs(p.a, p.q, z, settings);
    return std::pair{r.sweeps, r.status == pb::lcp::Status::solved};
  });
}
BENCHMARK(BM_Pgs)->Apply(sizes_and_families);

// The fixed-size PGS at n = 2 (the two-contact scene), same problems as BM_Pgs/2/0.
void BM_PgsFixed2(benchmark::State& state) {
  const std::vector<Problem> ps = problems(2, 0);
  std::vector<Eigen::Matrix2d> a(kProblems);
  std::vector<Eigen::Vector2d> q(kProblems);
  for (int t = 0; t < kProblems; ++t) a[t] = ps[t].a, q[t] = ps[t].q;
  const pb::lcp::PgsSettings settings = cold_start_settings();
  int t = 0;
  for (auto _ : state) {
    Eigen::Vector2d z = Eigen::Vector2d::Zero();
    const pb::lcp::PgsResult r = pb::lcp::pgs<2>(a[t], q[t], z, settings);
    benchmark::DoNotOptimize(z.data());
    benchmark::DoNotOptimize(r.sweeps);
    t = (t + 1) % kProblems;
  }
}
BENCHMARK(BM_PgsFixed2);

}  // namespace
