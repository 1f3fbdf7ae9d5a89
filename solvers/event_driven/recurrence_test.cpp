// The reference's recurrence on a record's sample intervals (DERIVATION.md §11): its
// transition is the oscillator's exact motion, its acceleration bound holds, and a solve that
// takes the intervals it proves empty by the recurrence gives the rows of the full event loop
// (detail::solve_searching_every_sample) to round-off, impacts and grazing touches included.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cases/case.hpp"
#include "cases/record.hpp"
#include "cases/system.hpp"
#include "kit/testing.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/event_driven/recurrence.hpp"
#include "solvers/event_driven/wave.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace recurrence_tests {

using event_driven::Recurrence;
using event_driven::Transition;

struct Motion {
  long double dx, dv;
};

// x'' + two_sigma x' + w2 x = q0 + q1 s from (x0, v0) over h, the closed form in long double:
// the particular solution alpha + beta s and the damped free motion of the rest.
Motion closed_form(long double two_sigma, long double w2, long double x0, long double v0, long double q0,
                   long double q1, long double h) {
  const long double sigma = two_sigma / 2.0L, wd = std::sqrt(w2 - sigma * sigma);
  const long double beta = q1 / w2, alpha = (q0 - two_sigma * beta) / w2;
  const long double a = x0 - alpha, b = (v0 - beta + sigma * a) / wd;
  const long double e = std::exp(-sigma * h), c = std::cos(wd * h), s = std::sin(wd * h);
  const long double x = alpha + beta * h + e * (a * c + b * s);
  const long double v = beta + e * ((wd * b - sigma * a) * c - (wd * a + sigma * b) * s);
  return {x - x0, v - v0};
}

struct Increments {
  double dx, dv;
};

Increments apply(const Transition& t, double x0, double v0, double q0, double q1) {
  return {t.d[0][0] * x0 + t.d[0][1] * v0 + t.d[0][2] * q0 + t.d[0][3] * q1,
          t.d[1][0] * x0 + t.d[1][1] * v0 + t.d[1][2] * q0 + t.d[1][3] * q1};
}

// From w h = 0.01 (a sample of a soft body) to 30 (the transition's halvings): each increment
// is the closed form's to 1e-14 of the motion's scale (the closed form's own cancellation,
// (w h)^-2 ulps of long double, stays below that from w h = 0.01).
TEST(Recurrence, TransitionIsTheOscillatorsExactMotionOverAnInterval) {
  const double w2 = 4.0, two_sigma = 0.2;  // w = 2, xi = 0.05
  for (const double wh : {0.01, 0.1, 0.6, 3.0, 30.0}) {
    const double h = wh / 2.0;
    const Transition t = event_driven::transition(two_sigma, w2, h);
    for (const auto& [x0, v0, q0, q1] : {std::array<double, 4>{0.3, -0.7, 1.1, -25.0},
                                         std::array<double, 4>{-1e-3, 2.0, -0.4, 3.0}}) {
      const Increments got = apply(t, x0, v0, q0, q1);
      const Motion want = closed_form(two_sigma, w2, x0, v0, q0, q1, h);
      const double scale = std::abs(x0) + std::abs(v0) / 2.0 + (std::abs(q0) + std::abs(q1) * h) / w2;
      EXPECT_NEAR(got.dx, static_cast<double>(want.dx), 1e-14 * scale) << "w h = " << wh;
      EXPECT_NEAR(got.dv, static_cast<double>(want.dv), 2e-14 * scale) << "w h = " << wh;
    }
  }
}

// Two steps of h / 2 (the load's ramp continued: q0 + q1 h / 2 at the midpoint) are one step
// of h to round-off, for a step far below the closed form's reach (w h = 1e-4), where each
// increment is the ramp's h^3 / 6 against terms of size h.
TEST(Recurrence, TwoHalfStepsAreOneStep) {
  const double w2 = 0.16, two_sigma = 0.04, h = 2.5e-4;
  const Transition full = event_driven::transition(two_sigma, w2, h);
  const Transition half = event_driven::transition(two_sigma, w2, h / 2.0);
  const double x0 = 0.02, v0 = -0.003, q0 = 0.5, q1 = 40.0;
  const Increments one = apply(full, x0, v0, q0, q1);
  const Increments first = apply(half, x0, v0, q0, q1);
  const Increments second = apply(half, x0 + first.dx, v0 + first.dv, q0 + q1 * h / 2.0, q1);
  EXPECT_NEAR(first.dx + second.dx, one.dx, 1e-15 * std::abs(one.dx));
  EXPECT_NEAR(first.dv + second.dv, one.dv, 1e-14 * std::abs(one.dv));
}

// |x''| stays within the bound over the whole of a long linear load (twenty periods), and the
// bound is not loose by more than the free motion's own decay allows at the start.
TEST(Recurrence, AccelerationBoundHoldsWhileTheLoadIsLinear) {
  const double m = 2.0, c = 0.4, k = 18.0;  // w = 3, xi = 1/30
  const Recurrence r(m, c, k);
  ASSERT_TRUE(r.valid());
  const double x0 = 0.1, v0 = -0.5, q0 = 0.8, q1 = -0.3;
  const double bound = r.acceleration_bound(x0, v0, q0, q1);
  event_driven::Forcing load;
  load.f0 = m * q0;
  load.f1 = m * q1;
  event_driven::Wave x;
  event_driven::oscillator_into(x, 0.0, x0, v0, m, c, k, load, std::numeric_limits<double>::infinity());
  double largest = 0.0;
  for (int i = 0; i <= 20000; ++i) {
    double d[3];
    x.eval(i * 20.0 * 2.0 * std::numbers::pi / 3.0 / 20000.0, d, 3);
    largest = std::max(largest, std::abs(d[2]));
  }
  EXPECT_LE(largest, bound);
  EXPECT_GT(largest, 0.5 * bound);
}

// The lengths of a run's intervals get one number each, the same number for the same bits.
TEST(Recurrence, LengthsNumberEachDistinctIntervalOnce) {
  event_driven::Lengths lengths;
  std::vector<double> t;
  for (int i = 0; i <= 8000; ++i) t.push_back(static_cast<double>(i) * 0.005);
  std::vector<int> seen;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    const int n = lengths.slot(t[i + 1] - t[i]);
    ASSERT_GE(n, 0);
    if (std::find(seen.begin(), seen.end(), n) == seen.end()) seen.push_back(n);
    EXPECT_EQ(lengths.slot(t[i + 1] - t[i]), n);
  }
  EXPECT_GT(seen.size(), 1u);  // 0.005 i rounds: several distinct differences
  EXPECT_LT(seen.size(), static_cast<std::size_t>(event_driven::Lengths::kMax));
  for (int i = 0; i < 2 * event_driven::Lengths::kMax; ++i) {  // full: it says so, and keeps the others
    const int n = lengths.slot(1.0 + i);
    EXPECT_TRUE(n < event_driven::Lengths::kMax);
  }
  EXPECT_EQ(lengths.slot(1.0 + 2 * event_driven::Lengths::kMax), -1);
}

// A case on a record: the record's own a_p and mean frequency as its scales.
Case on_record(Scene scene, const std::string& file, double pi2, double pi5) {
  Case c = test::make_case(scene, PulseShape::record, pi2, pi5, 0.5);
  c.samples = read_record(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/records/" + file);
  c.record = file;
  c.a_p = c.samples->peak;
  c.w_p = c.samples->mean_frequency();
  return c;
}

// The recurrence against the full event loop on records: the benchmark's pair with many
// impacts (bench/record_bench.cpp), a wall and a row of three on real records, a soft body
// (Pi2 = 0.1, where the full loop's own rebuilds drift most: DERIVATION.md §11). Impacts and
// contact phases are the same; Pi1 within 1e-9 (measured at most 8e-10 over the records-real
// set, where impacts amplify the full loop's round-off of a soft body; 1e-13 elsewhere), and
// 1e-11 without contact.
TEST(Recurrence, RecordsGiveTheFullEventLoopsRows) {
  std::vector<Case> cases;
  {
    Case c;  // bench/record_bench.cpp's
    c.scene = Scene::pair;
    c.pulse = PulseShape::record;
    c.samples = read_record(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/records/mp-noise-40s.csv");
    c.record = c.samples->source;
    c.a_p = c.samples->peak;
    c.w_p = 2.0 * std::numbers::pi;
    c.pi2 = 1.0;
    c.pi3 = 0.5;
    c.pi5 = 0.5;
    c.pi6 = 1.0;
    c.eps = 0.5;
    cases.push_back(c);
  }
  cases.push_back(on_record(Scene::wall, "real/TAN350.AT2", 0.1, 0.5));
  cases.push_back(on_record(Scene::wall, "real/ISE-WE.AT2", 0.5, 0.5));
  cases.push_back(on_record(Scene::row3, "real/A-PAS180.AT2", 1.0, 2.0));
  cases.push_back(on_record(Scene::pair, "real/CEM000.AT2", 0.1, 2.0));
  long impacts = 0;
  for (const Case& c : cases) {
    const System s = make_system(c);
    const Result fast = event_driven::solve(s, {});
    const Result full = event_driven::detail::solve_searching_every_sample(s, {});
    ASSERT_EQ(fast.status, Status::ok) << c.record << ": " << fast.message;
    ASSERT_EQ(full.status, Status::ok) << c.record << ": " << full.message;
    EXPECT_EQ(fast.impacts, full.impacts) << c.record;
    EXPECT_EQ(fast.contact_phases, full.contact_phases) << c.record;
    EXPECT_LT(test::rel(fast.pi1, full.pi1), 1e-9) << c.record;
    EXPECT_LT(std::abs(fast.steps - full.steps), 1 + full.steps / 100) << c.record;  // events: a few at round-off
    const double alone = event_driven::no_contact_pi1(s);
    System apart = s;
    apart.bodies = {s.bodies[ix(s.ref)]};
    apart.wall = false;
    apart.ref = 0;
    apart.u_start = {0.0};
    apart.v_start = {0.0};
    EXPECT_LT(test::rel(alone, event_driven::detail::solve_searching_every_sample(apart, {}).pi1), 1e-11) << c.record;
    impacts += fast.impacts;
  }
  EXPECT_GT(impacts, 50);  // the cases pound
}

// A free run (the separation's peaks, every body and every gap either way) is the full
// loop's to 1e-10 (a gap's extreme is a difference of two bodies' motions: its relative
// round-off is theirs times their ratio to it; measured 2e-11 over the records-real set).
TEST(Recurrence, FreeMotionOnRecordsIsTheFullEventLoops) {
  for (const auto& [scene, file, pi2] : {std::tuple{Scene::pair, "real/GCN-WE.AT2", 0.1},
                                         std::tuple{Scene::row3, "real/B-LAD180.AT2", 1.0}}) {
    const System s = make_system(on_record(scene, file, pi2, 0.5));
    const FreeMotion fast = event_driven::free_motion(s);
    const FreeMotion full = event_driven::detail::free_motion_searching_every_sample(s);
    ASSERT_EQ(fast.status, Status::ok) << fast.message;
    ASSERT_EQ(full.status, Status::ok) << full.message;
    ASSERT_EQ(fast.peak.size(), full.peak.size());
    for (std::size_t i = 0; i < full.peak.size(); ++i) EXPECT_LT(test::rel(fast.peak[i], full.peak[i]), 1e-11) << file;
    for (std::size_t j = 0; j < full.closing.size(); ++j) {
      EXPECT_LT(test::rel(fast.closing[j], full.closing[j]), 1e-10) << file;
      EXPECT_LT(test::rel(fast.opening[j], full.opening[j]), 1e-10) << file;
    }
  }
}

// The certificate: a body pushed towards the wall by a constant load reaches its first peak
// in the middle of a sample interval, where a gap chosen open at both ends of the interval
// closes. The bound cannot clear that interval, the full search runs and finds the impact; a
// gap a little wider than the peak has none, in either path.
TEST(Recurrence, ATouchInsideASampleIntervalIsFound) {
  Case c = test::make_case(Scene::wall, PulseShape::record, 1.0, 0.5, 0.5);
  const double w_p = 2.0 * std::numbers::pi;
  const double w0 = c.pi2 * w_p, xi = 0.05;
  const double sigma = xi * w0, wd = w0 * std::sqrt(1.0 - xi * xi);
  const double t_peak = std::numbers::pi / wd, dt = t_peak / 6.5;  // the peak mid-interval
  std::vector<double> t, a;
  for (int i = 0; i <= 40; ++i) {
    t.push_back(i * dt);
    a.push_back(1.0);  // a_g = 1: body 0 moves to -u_s (towards the wall), overshooting
  }
  c.samples = std::make_shared<const Record>(record_from_samples(t, a, "m"));
  c.record = "(in memory)";
  c.a_p = 1.0;
  c.w_p = w_p;
  c.xi = xi;
  System s = make_system(c);
  const double u_s = 1.0 / (w0 * w0);
  const auto u = [&](double time) {  // |u0| from rest under the step
    return u_s * (1.0 - std::exp(-sigma * time) * (std::cos(wd * time) + sigma / wd * std::sin(wd * time)));
  };
  const double peak = u(t_peak), ends = std::max(u(6.0 * dt), u(7.0 * dt));
  ASSERT_LT(ends, peak);
  for (const auto& [delta, touches] : {std::pair{peak - 0.05 * (peak - ends), true}, std::pair{peak * (1.0 + 1e-6), false}}) {
    s.delta = delta;
    const Result fast = event_driven::solve(s, {});
    const Result full = event_driven::detail::solve_searching_every_sample(s, {});
    ASSERT_EQ(fast.status, Status::ok) << fast.message;
    ASSERT_EQ(full.status, Status::ok) << full.message;
    EXPECT_EQ(fast.impacts > 0, touches);
    EXPECT_EQ(fast.impacts, full.impacts);
    EXPECT_LT(test::rel(fast.pi1, full.pi1), 1e-12);
  }
}

// The peak's certificate: a body released from U0 under a constant load swings to a far side
// 1e-3 beyond U0, in the middle of a sample interval whose samples both stay below U0. The
// bound cannot clear that interval; the search finds the swing, where its closed form puts it.
TEST(Recurrence, APeakInsideASampleIntervalIsFound) {
  Case c = test::make_case(Scene::wall, PulseShape::record, 1.0, 0.5, 0.5);
  const double w_p = 2.0 * std::numbers::pi, w0 = c.pi2 * w_p, xi = 0.05;
  const double sigma = xi * w0, wd = w0 * std::sqrt(1.0 - xi * xi);
  const double t_peak = std::numbers::pi / wd, dt = t_peak / 6.5;
  const double u0 = 0.01, decay = std::exp(-sigma * t_peak), beyond = 1e-3;
  // From rest at U0 about -u_s: the far side -u_s - (U0 + u_s) decay = -U0 (1 + beyond).
  const double u_s = u0 * (1.0 + beyond - decay) / (1.0 + decay);
  std::vector<double> t, a;
  for (int i = 0; i <= 20; ++i) {
    t.push_back(i * dt);
    a.push_back(u_s * w0 * w0);  // a_g pushes body 0 towards -u_s
  }
  c.samples = std::make_shared<const Record>(record_from_samples(t, a, "m"));
  c.record = "(in memory)";
  c.a_p = u_s * w0 * w0;
  c.w_p = w_p;
  c.xi = xi;
  System s = make_system(c);
  s.delta = 1e3 * u0;  // the wall far away
  s.u_start = {u0};
  s.v_start = {0.0};
  const auto u = [&](double time) {
    return -u_s + (u0 + u_s) * std::exp(-sigma * time) * (std::cos(wd * time) + sigma / wd * std::sin(wd * time));
  };
  ASSERT_LT(std::max(std::abs(u(6.0 * dt)), std::abs(u(7.0 * dt))), u0);
  const Result fast = event_driven::solve(s, {});
  const Result full = event_driven::detail::solve_searching_every_sample(s, {});
  ASSERT_EQ(fast.status, Status::ok) << fast.message;
  EXPECT_EQ(fast.impacts, 0);
  EXPECT_LT(test::rel(fast.pi1, full.pi1), 1e-12);
  EXPECT_LT(test::rel(fast.pi1 * s.length_scale(), u0 * (1.0 + beyond)), 1e-12);
  EXPECT_NEAR(fast.t_max, t_peak, 1e-9);
}

// Yielding bodies keep the full event loop (their branch changes the motion): the same bits.
TEST(Recurrence, YieldingBodiesKeepTheFullEventLoop) {
  Case c = test::yielding_case(Scene::pair, PulseShape::record, 1.0, 0.5, 0.5, 0.3, 0.1);
  c.samples = read_record(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/records/mp-noise-20s.csv");
  c.record = "mp-noise-20s.csv";
  c.a_p = c.samples->peak;
  c.w_p = 2.0 * std::numbers::pi;
  const System s = make_system(c);
  const Result fast = event_driven::solve(s, {});
  const Result full = event_driven::detail::solve_searching_every_sample(s, {});
  ASSERT_EQ(full.status, Status::ok) << full.message;
  EXPECT_EQ(fast.pi1, full.pi1);
  EXPECT_EQ(fast.steps, full.steps);
  EXPECT_EQ(fast.impacts, full.impacts);
}

}  // namespace recurrence_tests
}  // namespace pb
