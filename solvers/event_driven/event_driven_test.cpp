// The event-driven reference against closed forms, exact properties and its own
// tolerances. It is the ground truth of every other solver, so these tolerances are tight.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "cases/system.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/event_driven/impact.hpp"
#include "kit/lcp/enumerate.hpp"
#include "solvers/registry.hpp"

namespace pb {
namespace {

Case pair_case(double pi2, double pi5, double pi6, PulseShape p = PulseShape::sine, double eps = 0.5) {
  Case c;
  c.scene = Scene::pair;
  c.pulse = p;
  c.pi2 = pi2;
  c.pi3 = 0.5;
  c.pi5 = pi5;
  c.pi6 = pi6;
  c.eps = eps;
  return c;
}

double pi1(const Case& c, double tol_scale = 1.0) {
  Settings st;
  st.tol_scale = tol_scale;
  const Result r = event_driven::solve(make_system(c), st);
  EXPECT_EQ(r.status, Status::ok) << r.message;
  return r.pi1;
}

// Duhamel's integral of the ground pulse for body 0 alone, by composite 5-point
// Gauss-Legendre quadrature: an independent route to the no-contact response.
double duhamel(const System& s, double t) {
  const Body& b = s.bodies[static_cast<std::size_t>(s.ref)];
  const double wd = b.w * std::sqrt(1.0 - s.xi * s.xi);
  const double end = std::min(t, s.pulse.duration());
  static constexpr std::array<double, 5> x = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                              0.9061798459386640};
  static constexpr std::array<double, 5> w = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                              0.2369268850561891, 0.2369268850561891};
  const int panels = 400;
  const double h = end / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    for (std::size_t k = 0; k < 5; ++k) {
      const double tau = h * (p + 0.5 + 0.5 * x[k]);
      sum += w[k] * 0.5 * h * s.pulse.accel(tau) * std::exp(-s.xi * b.w * (t - tau)) * std::sin(wd * (t - tau));
    }
  }
  return -sum / wd;
}

double duhamel_pi1(const System& s) {
  // Coarse scan, then golden-section refinement around the largest sample.
  const int n = 3000;
  double best = 0.0, t_best = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double t = s.t_end * i / n;
    const double u = std::abs(duhamel(s, t));
    if (u > best) {
      best = u;
      t_best = t;
    }
  }
  double lo = std::max(0.0, t_best - s.t_end / n), hi = std::min(s.t_end, t_best + s.t_end / n);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 80; ++it) {
    const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
    if (std::abs(duhamel(s, a)) > std::abs(duhamel(s, b)))
      hi = b;
    else
      lo = a;
  }
  return s.pi1(std::max(best, std::abs(duhamel(s, 0.5 * (lo + hi)))));
}

TEST(EventDriven, NoContactPi1MatchesDuhamelIntegral) {
  for (PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
    for (double pi2 : {0.3, 1.0, 2.7}) {
      const System s = make_system(pair_case(pi2, 2.0, 1.0, p));
      // 1e-10: the quadrature and the golden section are good to ~1e-13 here.
      EXPECT_NEAR(event_driven::no_contact_pi1(s), duhamel_pi1(s), 1e-10 * duhamel_pi1(s))
          << name(p) << " pi2=" << pi2;
    }
  }
}

TEST(EventDriven, Pi1IsTheSameAtAnyPulseScale) {
  for (Scene scene : {Scene::wall, Scene::pair, Scene::row3}) {
    for (PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
      Case c = pair_case(1.3, 0.5, 1.0, p);
      c.scene = scene;
      c.pi7 = 2.0;
      c.pi8 = 0.5;
      Case scaled = c;
      scaled.a_p = 3.7;
      scaled.w_p = 2.0 * std::numbers::pi * 1.9;
      const double a = pi1(c), b = pi1(scaled);
      // 1e-12: only round-off differs; the tolerances are relative to the pulse scales.
      EXPECT_NEAR(a, b, 1e-12 * a) << name(scene) << " " << name(p);
    }
  }
}

TEST(EventDriven, TighterTolerancesMovePi1LessThan1e9) {
  for (double eps : {0.0, 0.5, 1.0}) {
    for (Scene scene : {Scene::pair, Scene::row3}) {
      for (double pi2 : {0.4, 1.5, 4.0}) {
        Case c = pair_case(pi2, 0.5, 1.0, PulseShape::cosine, eps);
        c.scene = scene;
        c.pi7 = 0.5;
        c.pi8 = 1.0;
        const double a = pi1(c), b = pi1(c, 0.01);
        EXPECT_NEAR(a, b, 1e-9 * a) << name(scene) << " eps=" << eps << " pi2=" << pi2;
      }
    }
  }
}

TEST(EventDriven, WallIsTheLimitOfAPairWithAStiffHeavyNeighbour) {
  Case wall = pair_case(0.8, 1.0, 1.0, PulseShape::sine);
  wall.scene = Scene::wall;
  const double ref = pi1(wall);
  double previous = INFINITY;
  for (double pi : {1e-1, 1e-2, 1e-3}) {
    const double diff = std::abs(pi1(pair_case(0.8, pi, pi, PulseShape::sine)) - ref);
    EXPECT_LT(diff, previous) << "pi5 = pi6 = " << pi;
    previous = diff;
  }
  // The neighbour's own motion and recoil are O(Pi6) of body 0's.
  EXPECT_LT(previous, 1e-2 * ref);
}

TEST(EventDriven, PairInPhaseNeverTouches) {
  for (PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
    for (double pi2 : {0.2, 1.0, 5.0}) {
      const System s = make_system(pair_case(pi2, 1.0, 1.0, p));
      const Result r = event_driven::solve(s, {});
      EXPECT_EQ(r.impacts, 0);
      EXPECT_EQ(r.pi1, event_driven::no_contact_pi1(s));
    }
  }
}

TEST(EventDriven, WallImpactsAccumulateIntoPersistentContact) {
  Case c = pair_case(0.3, 1.0, 1.0, PulseShape::sine, 0.5);
  c.scene = Scene::wall;
  c.pi3 = 0.05;
  const Result r = event_driven::solve(make_system(c), {});
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_GT(r.impacts, 10);
  EXPECT_GE(r.contact_phases, 1);
  // The reference never lets a gap go below round-off of the pulse length.
  EXPECT_GT(r.min_gap, -1e-12 * make_system(c).length_scale());
}

System three_bodies(double m1, double m0, double m2) {
  Case c;
  c.scene = Scene::row3;
  c.pi6 = 1.0 / m1;
  c.pi8 = 1.0 / m2;
  System s = make_system(c);
  s.bodies[0].m = m1;
  s.bodies[1].m = m0;
  s.bodies[2].m = m2;
  return s;
}

TEST(PoissonImpact, ThreeEqualMassesGiveMinusOneThirdTwoThirdsTwoThirds) {
  const System s = three_bodies(1.0, 1.0, 1.0);
  std::vector<double> v = {1.5, 0.0, 0.0};  // body 1 strikes body 0, which touches body 2
  const std::array<int, 2> set = {0, 1};
  event_driven::poisson_impact(s, set, v, 1.0);
  EXPECT_NEAR(v[0], -0.5, 1e-15);
  EXPECT_NEAR(v[1], 1.0, 1e-15);
  EXPECT_NEAR(v[2], 1.0, 1e-15);
}

double momentum(const System& s, const std::vector<double>& v) {
  double p = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) p += s.bodies[i].m * v[i];
  return p;
}
double kinetic(const System& s, const std::vector<double>& v) {
  double e = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) e += 0.5 * s.bodies[i].m * v[i] * v[i];
  return e;
}

TEST(PoissonImpact, ConservesMomentumAndNeverGainsEnergy) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> mass(0.1, 10.0), vel(-2.0, 2.0), eps(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const System s = three_bodies(mass(rng), mass(rng), mass(rng));
    std::vector<double> v = {vel(rng), vel(rng), vel(rng)};
    const double p0 = momentum(s, v), e0 = kinetic(s, v);
    const bool both = trial % 2 == 0;
    const std::vector<int> set = both ? std::vector<int>{0, 1} : std::vector<int>{trial % 4 == 1 ? 0 : 1};
    const double e = trial % 3 == 0 ? 1.0 : eps(rng);
    const auto out = event_driven::poisson_impact(s, set, v, e);
    // Round-off of a few operations on O(10) numbers.
    EXPECT_NEAR(momentum(s, v), p0, 1e-13 * (1.0 + std::abs(p0)));
    EXPECT_LE(kinetic(s, v), e0 * (1.0 + 1e-13) + 1e-15);
    for (double g : out.gap_rate) EXPECT_GE(g, -1e-13);
    // One contact with eps = 1: Newton's and Poisson's laws coincide, energy is kept.
    if (!both && e == 1.0) {
      EXPECT_NEAR(kinetic(s, v), e0, 1e-13 * e0);
    }
  }
}

TEST(PoissonImpact, OneContactReversesTheApproachSpeedTimesEps) {
  const System s = three_bodies(2.0, 0.5, 1.0);
  for (double e : {0.0, 0.3, 1.0}) {
    std::vector<double> v = {1.0, -0.25, 0.0};
    const double before = event_driven::gap_rate(s, 0, v);
    const std::array<int, 1> set = {0};
    event_driven::poisson_impact(s, set, v, e);
    EXPECT_NEAR(event_driven::gap_rate(s, 0, v), -e * before, 1e-15);
  }
}

// Random runs of 3 to 11 contacts, some bodies already moving together (zero rates of
// either sign by rounding), some separating: both LCPs of every run, solved here by
// enumerating all active sets on the dense G, must give the velocities the solver gives
// (it uses Chandrasekaran's method on the tridiagonal G). Sets of several runs check that
// runs do not interact.
TEST(PoissonImpact, LongRunsMatchTheEnumerationOfBothLCPs) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> mass(0.1, 10.0), vel(-2.0, 2.0), unit(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 4 + trial % 9;
    Case c;
    c.scene = Scene::chain;
    c.bodies = n;
    System s = make_system(c);
    for (Body& b : s.bodies) b.m = mass(rng);
    std::vector<double> v(static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = i > 0 && unit(rng) < 0.4 ? v[i - 1] : vel(rng);
    std::vector<int> set;
    for (int j = 0; j + 1 < n; ++j)
      if (trial % 3 != 0 || unit(rng) < 0.8) set.push_back(j);
    const double e = trial % 4 == 0 ? 1.0 : unit(rng);

    // Reference: both LCPs on the dense G of the whole set (block diagonal across runs).
    const auto m = static_cast<Eigen::Index>(set.size());
    Eigen::MatrixXd g = Eigen::MatrixXd::Zero(m, m);
    Eigen::VectorXd gd(m);
    for (Eigen::Index a = 0; a < m; ++a) {
      const int j = set[static_cast<std::size_t>(a)];
      g(a, a) = 1.0 / s.bodies[static_cast<std::size_t>(j)].m + 1.0 / s.bodies[static_cast<std::size_t>(j + 1)].m;
      if (a > 0 && set[static_cast<std::size_t>(a - 1)] == j - 1)
        g(a, a - 1) = g(a - 1, a) = -1.0 / s.bodies[static_cast<std::size_t>(j)].m;
      gd(a) = event_driven::gap_rate(s, j, v);
    }
    const lcp::EnumerateResult comp = lcp::enumerate(g, gd);
    ASSERT_EQ(comp.status, lcp::Status::solved);
    const Eigen::VectorXd gd_c = g * comp.z + gd;
    const lcp::EnumerateResult exp = lcp::enumerate(g, gd_c + e * (g * comp.z));
    ASSERT_EQ(exp.status, lcp::Status::solved);
    const Eigen::VectorXd total = (1.0 + e) * comp.z + exp.z;
    std::vector<double> expected = v;
    for (Eigen::Index a = 0; a < m; ++a) {
      const auto j = static_cast<std::size_t>(set[static_cast<std::size_t>(a)]);
      expected[j] -= total(a) / s.bodies[j].m;
      expected[j + 1] += total(a) / s.bodies[j + 1].m;
    }

    const auto out = event_driven::poisson_impact(s, set, v, e);
    // Rounding of O(10) operations on velocities of O(1) (measured ~1e-15); contacts at
    // rest relative to each other count as at rest to 1e-13 of the speed.
    for (std::size_t i = 0; i < v.size(); ++i) EXPECT_NEAR(v[i], expected[i], 1e-11) << "trial " << trial;
    for (double rate : out.gap_rate) EXPECT_GE(rate, -1e-12) << "trial " << trial;
  }
}

TEST(EventDriven, CheckRejectsAStepOfAnyKind) {
  Settings st;
  EXPECT_EQ(event_driven::check(st), "");
  st.wh = 2.0;
  EXPECT_EQ(event_driven::check(st), "wh: the event-driven solver takes no step");
  st.wh = 0.0;
  st.steps = 64;
  EXPECT_FALSE(event_driven::check(st).empty());
  st.steps = 0;
  st.variant = "quickstep";
  EXPECT_FALSE(event_driven::check(st).empty());
}

}  // namespace
}  // namespace pb

namespace pb {
namespace {

// Case i of a random sweep over the whole parameter box: wall, pair and row3 in turn, the
// pulses in turn every three cases, every Pi over two decades around 1 and Pi3 around 0.3,
// or touching at rest (Pi3 = 0) in one case of every `touching_every`. eps is the caller's.
Case random_case(int i, int touching_every, std::mt19937& rng) {
  std::uniform_real_distribution<double> decade(-1.0, 1.0);
  Case c;
  c.scene = i % 3 == 0 ? Scene::wall : i % 3 == 1 ? Scene::pair : Scene::row3;
  c.pulse = (i / 3) % 2 ? PulseShape::cosine : PulseShape::sine;
  c.pi2 = std::pow(10.0, decade(rng));
  c.pi3 = i % touching_every == 0 ? 0.0 : std::pow(10.0, decade(rng) - 0.5);
  c.pi5 = std::pow(10.0, decade(rng));
  c.pi6 = std::pow(10.0, decade(rng));
  c.pi7 = std::pow(10.0, decade(rng));
  c.pi8 = std::pow(10.0, decade(rng));
  return c;
}

// The energy balance changes only at events, where impacts lose energy and the rest is
// rounding: over random wall, pair and row3 cases its largest excess stays at rounding
// (measured 1.8e-14 over the shipped case sets), and every isolated impact restitutes eps
// (measured within 2.2e-13: the rounding of velocities ~1e3 times the slowest approach
// counted, kRestitutionFloor a_p / w_p).
TEST(EventDriven, EnergyBalanceAndRestitutionOfIsolatedImpactsAreExactToRounding) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  long isolated = 0;
  for (int i = 0; i < 600; ++i) {
    Case c = random_case(i, 5, rng);
    c.eps = i % 4 == 0 ? 1.0 : unit(rng);
    const Result r = event_driven::solve(make_system(c), {});
    ASSERT_EQ(r.status, Status::ok) << "case " << i << ": " << r.message;
    EXPECT_LE(r.energy_excess, 1e-12) << "case " << i;
    isolated += r.isolated_impacts;
    if (r.isolated_impacts > 0) {
      EXPECT_NEAR(r.restitution_low, c.eps, 1e-11) << "case " << i;
      EXPECT_NEAR(r.restitution_high, c.eps, 1e-11) << "case " << i;
    }
  }
  EXPECT_GT(isolated, 1000);
}

// Random cases over the whole parameter box, a seventh of them touching at rest (Pi3 = 0),
// a quarter plastic and a quarter elastic: the reference must finish every one, never let
// a gap open below round-off, and stay within its event budget.
TEST(EventDriven, EveryRandomCaseFinishesWithoutPenetration) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 3000; ++i) {
    Case c = random_case(i, 7, rng);
    c.directivity = (i / 6) % 2 ? Directivity::reverse : Directivity::normal;
    const double e = unit(rng);
    c.eps = i % 4 == 0 ? 0.0 : i % 4 == 1 ? 1.0 : e;
    const System s = make_system(c);
    Settings st;
    st.step_cap = 200000;
    const Result r = event_driven::solve(s, st);
    ASSERT_EQ(r.status, Status::ok) << "case " << i << ": " << r.message;
    ASSERT_TRUE(std::isfinite(r.pi1)) << "case " << i;
    // A gap goes below zero only where a contact sits within round-off of closed and is
    // caught where it passes the closure tolerance, 1e-10 of the pulse length.
    ASSERT_GT(r.min_gap, -1.01e-10 * s.length_scale()) << "case " << i;
  }
}

}  // namespace
}  // namespace pb
