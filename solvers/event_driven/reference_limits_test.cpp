// The reference at the edges of its domain: undamped systems at, near and away from
// resonance (against solutions that do not use its closed form), the bounds of its
// tolerances, and runs that must end when told to, with a status that says why.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <thread>
#include <vector>

#include "cases/system.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/event_driven/search.hpp"
#include "solvers/event_driven/wave.hpp"
#include "sweep/sweep.hpp"
#include "solvers/registry.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace reference_limits_tests {

Case undamped(Scene scene, PulseShape pulse, double pi2) {
  Case c;
  c.scene = scene;
  c.pulse = pulse;
  c.pi2 = pi2;
  c.pi3 = 0.5;
  c.eps = 0.5;
  c.xi = 0.0;
  return c;
}

// u'' + 2 xi w u' + w^2 u = -a_g(t) from rest by Duhamel's integral,
// u(t) = -int a_g(tau) exp(-xi w (t - tau)) sin(wd (t - tau)) / wd dtau, by composite 5-point
// Gauss-Legendre quadrature: it never divides by w^2 - w_p^2.
double duhamel(const System& s, double t) {
  static constexpr std::array<double, 5> x = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                              0.9061798459386640};
  static constexpr std::array<double, 5> g = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                              0.2369268850561891, 0.2369268850561891};
  const double w = s.bodies[0].w, wd = w * std::sqrt(1.0 - s.xi * s.xi);
  const double end = std::min(t, s.pulse.duration());
  const int panels = 100;
  const double h = end / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p)
    for (std::size_t k = 0; k < 5; ++k) {
      const double tau = h * (p + 0.5 + 0.5 * x[k]);
      sum += g[k] * 0.5 * h * s.pulse.accel(tau) * std::exp(-s.xi * w * (t - tau)) * std::sin(wd * (t - tau));
    }
  return -sum / wd;
}

// Largest |u| over [0, t_end]: a scan, then golden sections around every sampled local
// maximum within 1e-3 of the largest (near resonance the peaks of successive cycles differ
// by less than the scan's sampling error), on each side of T_p (where u'' jumps, so |u|
// need not be unimodal across it).
double duhamel_pi1(const System& s) {
  const auto u = [&](double t) { return std::abs(duhamel(s, t)); };
  const auto golden = [&](double lo, double hi) {
    const double r = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 80; ++it) {
      const double a = hi - r * (hi - lo), b = lo + r * (hi - lo);
      if (u(a) > u(b))
        hi = b;
      else
        lo = a;
    }
    return u(0.5 * (lo + hi));
  };
  const int n = 1000;
  const double dt = s.t_end / n, tp = s.pulse.duration();
  std::vector<double> sample(n + 1);
  for (int i = 0; i <= n; ++i) sample[static_cast<std::size_t>(i)] = u(dt * i);
  const double top = *std::max_element(sample.begin(), sample.end());
  double best = std::max(top, u(tp));
  for (int i = 0; i <= n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (sample[k] < (1.0 - 1e-3) * top || (i > 0 && sample[k - 1] > sample[k]) || (i < n && sample[k + 1] > sample[k]))
      continue;
    const double lo = std::max(0.0, dt * (i - 1)), hi = std::min(s.t_end, dt * (i + 1));
    if (lo < tp && tp < hi)
      best = std::max({best, golden(lo, tp), golden(tp, hi)});
    else
      best = std::max(best, golden(lo, hi));
  }
  return s.pi1(best);
}

TEST(ReferenceResonance, NoContactMatchesDuhamelAtNearAndAwayFromResonance) {
  // Undamped, Pi2 = 1 + 4e-16 is a point of the stress set's grid: the closed form used to
  // lose everything there (0.57 a_p / w_p^2 off) and to hang at Pi2 = 1. Light damping
  // crosses the switch to the near-resonant form at |i w - z| = kNearResonance w.
  for (PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
    for (double pi2 : {1.0, 1.0 + 4e-16, 1.0 - 1e-12, 1.0 + 1e-7, 1.0 + 1e-3, 1.0 + 2e-2, 0.5, 2.0}) {
      const System s = make_system(undamped(Scene::wall, p, pi2));
      const double exact = duhamel_pi1(s);
      // 1e-10: the quadrature and golden section are good to ~1e-12 here.
      EXPECT_NEAR(event_driven::no_contact_pi1(s), exact, 1e-10 * exact) << name(p) << " pi2 = " << pi2;
    }
    for (double xi : {1e-12, 1e-6, 0.0049, 0.0051, 0.02}) {
      Case c = undamped(Scene::wall, p, 1.0);
      c.xi = xi;
      const System s = make_system(c);
      const double exact = duhamel_pi1(s);
      EXPECT_NEAR(event_driven::no_contact_pi1(s), exact, 1e-10 * exact) << name(p) << " xi = " << xi;
    }
  }
}

// The wall scene by an integrator that shares nothing with the reference: classical RK4 at
// a fine fixed step, each gap closure located by bisection on the step length and followed
// by v -> -eps v. Good to ~1e-9 for isolated impacts (no accumulation, no sticking).
double integrate_wall(const System& s, long& impacts) {
  const Body& b = s.bodies[0];
  const auto accel = [&](double t, double u, double v) { return -s.pulse.accel(t) - b.k / b.m * u - b.c / b.m * v; };
  const auto rk4 = [&](double t, double& u, double& v, double h) {
    const double k1u = v, k1v = accel(t, u, v);
    const double k2u = v + 0.5 * h * k1v, k2v = accel(t + 0.5 * h, u + 0.5 * h * k1u, v + 0.5 * h * k1v);
    const double k3u = v + 0.5 * h * k2v, k3v = accel(t + 0.5 * h, u + 0.5 * h * k2u, v + 0.5 * h * k2v);
    const double k4u = v + h * k3v, k4v = accel(t + h, u + h * k3u, v + h * k3v);
    u += h / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
    v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  };
  const double tp = s.pulse.duration();
  const double h0 = s.t_min / 20000.0;
  double t = 0.0, u = 0.0, v = 0.0, peak = 0.0;
  impacts = 0;
  while (t < s.t_end) {
    // Steps end at T_p, where the load has a kink.
    double h = std::min({h0, s.t_end - t, t < tp ? tp - t : h0});
    double un = u, vn = v;
    rk4(t, un, vn, h);
    if (s.delta + un < 0.0) {
      double lo = 0.0, hi = h;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        double um = u, vm = v;
        rk4(t, um, vm, mid);
        (s.delta + um < 0.0 ? hi : lo) = mid;
      }
      h = hi;
      un = u, vn = v;
      rk4(t, un, vn, h);
      un = -s.delta;
      vn = -s.eps * vn;
      ++impacts;
    }
    t += h;
    u = un, v = vn;
    peak = std::max(peak, std::abs(u));
  }
  return s.pi1(peak);
}

TEST(ReferenceResonance, UndampedWallImpactsMatchAnIndependentIntegration) {
  // The hanging input (sine, normal, Pi2 = 1, Pi3 = 0.5, eps = 0.5, xi = 0), its
  // near neighbours, and points away from resonance.
  for (double pi2 : {1.0, 1.0 + 4e-16, 1.0 + 1e-3, 0.7, 1.6}) {
    const System s = make_system(undamped(Scene::wall, PulseShape::sine, pi2));
    const Result r = event_driven::solve(s, {});
    ASSERT_EQ(r.status, Status::ok) << r.message;
    long impacts = 0;
    const double independent = integrate_wall(s, impacts);
    EXPECT_EQ(r.impacts, impacts) << "pi2 = " << pi2;
    // 1e-7: RK4 at T_min / 20000 with bisected impacts, measured ~1e-9 from the reference.
    EXPECT_NEAR(r.pi1, independent, 1e-7 * independent) << "pi2 = " << pi2;
  }
}

TEST(ReferenceResonance, ResonantBodyOfAPairAndAResonantStuckClusterFinish) {
  // Body 1 resonant (w1 = w0 / Pi5 = w_p); and a pair that sticks (eps = 0, touching) with
  // the cluster's frequency sqrt((k0 + k1) / (m0 + m1)) = w_p: Pi2^2 (1 + 1/Pi5^2) / 2 = 1.
  Case body1 = undamped(Scene::pair, PulseShape::sine, 0.5);
  body1.pi5 = 0.5;
  body1.pi6 = 0.5;
  Case cluster = undamped(Scene::pair, PulseShape::cosine, std::sqrt(1.6));
  cluster.pi5 = 2.0;
  cluster.pi6 = 1.0;
  cluster.pi3 = 0.0;
  cluster.eps = 0.0;
  for (const Case& c : {body1, cluster}) {
    const Result r = event_driven::solve(make_system(c), {});
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_TRUE(std::isfinite(r.pi1));
    // Resonance within one pulse: Pi1 stays of order pi (t sin grows by pi per period).
    EXPECT_LT(r.pi1, 100.0);
    // Self-similar, as every reference answer is.
    Case scaled = c;
    scaled.a_p = 9.81;
    scaled.w_p = 7.0;
    const Result rs = event_driven::solve(make_system(scaled), {});
    EXPECT_NEAR(rs.pi1, r.pi1, 1e-9 * r.pi1);
  }
}

// Issue 32's case: undamped, body 1 resonant with the pulse (Pi5 = 4 at Pi2 = 4) and body 0
// at four times its frequency, whose peak search once took 40 times its neighbours' time
// (search_test.cpp holds the cost; solvers/event_driven/event_driven_bench.cpp BM_EventDrivenPowerOfTwoPi2
// times it). The answer at Pi2 = 4 is its neighbours' limit: the same impacts, and Pi1 their
// mean to O(delta^2) (measured 1.5e-10 relative at delta = 5e-5; 1e-8 leaves room).
TEST(ReferenceResonance, Pi2OfFourIsItsNeighboursLimit) {
  const auto solve = [](double pi2) {
    Case c = undamped(Scene::pair, PulseShape::sine, pi2);
    c.pi5 = 4.0;
    c.pi6 = 1.0;
    return event_driven::solve(make_system(c), {});
  };
  const double delta = 5e-5;
  const Result below = solve(4.0 - delta), at = solve(4.0), above = solve(4.0 + delta);
  ASSERT_EQ(at.status, Status::ok) << at.message;
  EXPECT_EQ(at.impacts, 53);  // the count
  EXPECT_EQ(at.impacts, below.impacts);
  EXPECT_EQ(at.impacts, above.impacts);
  EXPECT_NEAR(at.pi1, 0.5 * (below.pi1 + above.pi1), 1e-8 * at.pi1);
}

TEST(ReferenceTolerances, CheckRefusesTolScalesDoublePrecisionCannotMean) {
  Settings st;
  for (double bad : {1e-320, 1e-6, 0.0, -1.0, 1e5, std::nan(""), std::numeric_limits<double>::infinity()}) {
    st.tol_scale = bad;
    EXPECT_EQ(event_driven::check(st).rfind("tol-scale:", 0), 0u) << bad;
  }
  for (double good : {event_driven::kMinTolScale, 0.01, 1.0, event_driven::kMaxTolScale}) {
    st.tol_scale = good;
    EXPECT_EQ(event_driven::check(st), "") << good;
  }
}

TEST(ReferenceTolerances, TightestAndLoosestTolScalesFinishAndAgree) {
  Case c = undamped(Scene::row3, PulseShape::cosine, 1.3);
  c.xi = 0.05;
  c.pi5 = 0.5;
  c.pi7 = 2.0;
  c.pi8 = 0.5;
  Settings tight, loose;
  tight.tol_scale = event_driven::kMinTolScale;
  loose.tol_scale = event_driven::kMaxTolScale;
  const Result a = event_driven::solve(make_system(c), tight), b = event_driven::solve(make_system(c), loose);
  ASSERT_EQ(a.status, Status::ok) << a.message;
  ASSERT_EQ(b.status, Status::ok) << b.message;
  // 1e-4: the loosest tolerances close gaps to 1e-6 a_p / w_p^2 and end accumulations at
  // 1e-3 a_p / w_p.
  EXPECT_NEAR(a.pi1, b.pi1, 1e-4 * a.pi1);
}

TEST(ReferenceLimits, AStopFlagEndsARunInsideItsSearches) {
  std::atomic<bool> stop{true};
  Settings st;
  st.stop = &stop;
  const Result r = event_driven::solve(make_system(undamped(Scene::pair, PulseShape::sine, 0.8)), st);
  EXPECT_EQ(r.status, Status::time_limit);
  EXPECT_NE(r.message.find("stopped"), std::string::npos) << r.message;
}

TEST(ReferenceLimits, ASearchThatCannotEndThrowsOutOfTime) {
  // A wave that grazes zero everywhere: f = 1e-300 (1 - cos t) keeps every window
  // undecided down to the floor. With a deadline that has already passed, the first
  // look at it ends the search.
  event_driven::Wave f = event_driven::constant(0.0, 1e-300);
  f.mode[0].omega = 1.0;
  f.mode[0].a = -1.0;
  f.n_modes = 1;
  f.prepare();
  std::atomic<bool> stop{true};
  Settings st;
  st.stop = &stop;
  Deadline deadline(st);
  EXPECT_THROW(event_driven::first_root(f, 1.0, 100.0, 1e-300, 1e-3, 0.0, deadline), event_driven::OutOfTime);
}

TEST(ReferenceLimits, NonFiniteMotionIsReportedNotSearched) {
  event_driven::Wave f = event_driven::constant(0.0, 1.0);
  f.mode[0].sigma = 0.1;
  f.mode[0].omega = 1.0;
  f.mode[0].a = std::nan("");
  f.n_modes = 1;
  f.prepare();
  Deadline deadline(Settings{});
  EXPECT_THROW(event_driven::first_root(f, 0.0, 10.0, 1e-12, 1e-4, 1e-10, deadline), event_driven::NonFinite);
}

TEST(ReferenceLimits, OwnChecksTurnAWrongAnswerIntoAStatusThatNamesIt) {
  const System s = make_system(undamped(Scene::wall, PulseShape::sine, 0.8));
  Result sunk;
  sunk.pi1 = 1.0;
  sunk.energy_excess = 0.0;
  sunk.min_gap = -1e-6 * s.length_scale();
  event_driven::check_result(s, 1.0, sunk);
  EXPECT_EQ(sunk.status, Status::penetration);
  EXPECT_NE(sunk.message.find("gap"), std::string::npos);

  Result heated;
  heated.pi1 = 1.0;
  heated.energy_excess = 1e-6;
  event_driven::check_result(s, 1.0, heated);
  EXPECT_EQ(heated.status, Status::energy);

  Result fine;
  fine.pi1 = 1.0;
  fine.energy_excess = 1e-13;
  fine.min_gap = -1.0005e-10 * s.length_scale();
  event_driven::check_result(s, 1.0, fine);
  EXPECT_EQ(fine.status, Status::ok) << fine.message;
}

TEST(SweepLimits, APointPastTheSweepsTimeLimitEndsAsTimeLimitAndTheSweepGoesOn) {
  // A 100-body chain takes far longer than a microsecond; the wall case is quick but still
  // past it. Every point gets a row, each with status time-limit.
  Case chain;
  chain.scene = Scene::chain;
  chain.bodies = 100;
  chain.pi2 = 1.0;
  chain.pi3 = 0.1;
  chain.eps = 0.0;
  const std::array cases = {chain, undamped(Scene::wall, PulseShape::sine, 0.8), chain};
  SweepOptions options;
  options.threads = 2;
  options.point_time_limit = 1e-6;
  const std::vector<Row> rows = run_sweep(cases, *find_solver("event-driven"), Settings{}, options);
  ASSERT_EQ(rows.size(), cases.size());
  for (const Row& row : rows) EXPECT_EQ(row.result.status, Status::time_limit) << row.point << row.result.message;
}

TEST(SweepLimits, ARunsOwnTimeLimitWinsOverTheSweepsDefault) {
  const std::array cases = {undamped(Scene::wall, PulseShape::sine, 0.8)};
  SweepOptions options;
  options.point_time_limit = 1e-9;
  Settings own;
  own.time_limit = 600.0;
  const std::vector<Row> rows = run_sweep(cases, *find_solver("event-driven"), own, options);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].result.status, Status::ok) << rows[0].result.message;
}

// A solver that never finishes on its own: it ends only when its Deadline passes.
Result endless(const System&, const Settings& settings) {
  Deadline deadline(settings);
  long k = 0;
  while (!deadline.passed(++k)) {
  }
  Result r;
  r.status = Status::time_limit;
  r.message = deadline.reason();
  return r;
}
std::string nothing(const Settings&) { return {}; }

TEST(SweepLimits, AStoppedSweepDropsThePointsItCutShort) {
  // Points cut short by the stop would read as time-limit rows; they must not be reported
  // (a resumed sweep solves them again), and the stop must not wait for them to end.
  const SolverInfo solver{"endless", "never ends", &endless, &nothing, &nothing};
  Case c;
  c.scene = Scene::wall;
  const std::array cases = {c, c, c};
  std::atomic<bool> stop{false};
  SweepOptions options;
  options.threads = 2;
  options.cancel = &stop;
  options.point_time_limit = 0.0;  // only the stop can end them
  std::jthread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    stop = true;
  });
  const std::vector<Row> rows = run_sweep(cases, solver, Settings{}, options);
  EXPECT_TRUE(rows.empty());
}

}  // namespace reference_limits_tests
}  // namespace pb
