// The reference with yielding bodies (DERIVATION.md §10): the general mode's closed form
// against sums that do not use it, the elastic limit, self-similarity, and the energy
// balance input = kinetic + elastic + damped + hysteretic + impact losses. Its agreement with
// an integration of its own (SciPy) is tests/yielding_independent_test.py.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "cases/case.hpp"
#include "cases/record.hpp"
#include "cases/system.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/event_driven/wave.hpp"
#include "kit/testing.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace yielding_reference_tests {

using event_driven::Forcing;
using event_driven::Wave;

constexpr double kInf = std::numeric_limits<double>::infinity();

// x'' + 2 sigma x' + k_m x = c2 + c3 s from (x0, v0), by the Taylor series of the motion in
// long double at small steps: each step's series from the equation itself (x^(n+2) =
// c-terms - 2 sigma x^(n+1) - k_m x^(n)), 30 terms, steps of 1/64 of the shortest time scale.
// It divides by nothing, so it holds at critical damping and without stiffness alike.
std::array<long double, 2> taylor_motion(long double x0, long double v0, long double sigma, long double k_m,
                                         long double c2, long double c3, long double t) {
  const long double scale = std::max({std::sqrt(k_m), 2.0L * sigma, 1.0L});
  const int steps = std::max(1, static_cast<int>(std::ceil(t * scale * 64.0L)));
  const long double h = t / steps;
  long double x = x0, v = v0, s = 0.0L;
  for (int n = 0; n < steps; ++n) {
    long double d[32];
    d[0] = x;
    d[1] = v;
    for (int k = 0; k + 2 < 32; ++k) {
      const long double load = k == 0 ? c2 + c3 * s : k == 1 ? c3 : 0.0L;
      d[k + 2] = load - 2.0L * sigma * d[k + 1] - k_m * d[k];
    }
    long double nx = 0.0L, nv = 0.0L, hk = 1.0L;
    for (int k = 0; k < 31; ++k) {
      nx += d[k] * hk;
      nv += d[k + 1] * hk;
      hk *= h / (k + 1);
    }
    x = nx;
    v = nv;
    s += h;
  }
  return {x, v};
}

// A softened cluster's closed form (the general mode) in every damping regime and without
// stiffness: its value and rate against the Taylor sums, relative to the motion's scale.
TEST(YieldingReference, GeneralModeIsTheMotionInEveryDampingRegime) {
  struct Regime {
    const char* name;
    double m, c, k;
  };
  const Regime regimes[] = {
      {"underdamped", 1.0, 0.1, 1.0},       {"near critical, under", 1.0, 2.0 - 1e-9, 1.0},
      {"critical", 1.0, 2.0, 1.0},          {"near critical, over", 1.0, 2.0 + 1e-9, 1.0},
      {"overdamped", 1.0, 10.0, 1.0},       {"alpha 1e-6 (slow root 1e-5)", 1.0, 0.1, 1e-6},
      {"no stiffness", 1.0, 0.1, 0.0},      {"no stiffness, no damping", 1.0, 0.0, 0.0},
      {"stiff, overdamped", 2.0, 60.0, 50.0}};
  for (const Regime& r : regimes) {
    Forcing load;
    load.f0 = -0.7;
    load.f1 = 0.3;
    const double x0 = 0.4, v0 = -1.3;
    Wave w;
    event_driven::general_oscillator_into(w, 2.0, x0, v0, r.m, r.c, r.k, load, 40.0);
    for (double s : {1e-9, 1e-5, 0.01, 0.3, 1.0, 2.5, 7.0, 20.0}) {
      double got[2];
      w.eval(2.0 + s, got, 2);
      const auto want = taylor_motion(x0, v0, 0.5L * r.c / r.m, static_cast<long double>(r.k) / r.m,
                                      static_cast<long double>(load.f0) / r.m, static_cast<long double>(load.f1) / r.m,
                                      s);
      const double scale = 1.0 + std::abs(static_cast<double>(want[0])) + std::abs(static_cast<double>(want[1]));
      EXPECT_NEAR(got[0], static_cast<double>(want[0]), 1e-13 * scale) << r.name << " s=" << s;
      EXPECT_NEAR(got[1], static_cast<double>(want[1]), 1e-13 * scale) << r.name << " s=" << s;
    }
  }
}

// Near t0 the value is its start plus increments, each to its own round-off: a motion that
// starts at rest under no load stays exactly at its start, and one that starts at x0 moves
// by v0 s to the relative round-off of v0 s (what lets a yield function that starts at zero
// be searched, as a gap is).
TEST(YieldingReference, GeneralModeResolvesIncrementsBelowTheValuesRoundOff) {
  Forcing none;
  Wave w;
  event_driven::general_oscillator_into(w, 1.0, 1e6, 2.0, 1.0, 0.3, 1e-4, none, 10.0);
  for (double s : {1e-12, 1e-9, 1e-6}) {
    double got[2];
    w.eval(1.0 + s, got, 2);
    const double moved = got[0] - 1e6;  // exact: both near 1e6, the difference is an ulp-resolved
    EXPECT_NEAR(moved, 2.0 * s, 1e-9 + 1e6 * 4e-16) << s;
  }
}

// The derivative of a general mode's wave is its rate, and the bounds the searches read hold
// on every sampled point up to the horizon, in every regime.
TEST(YieldingReference, GeneralModeBoundsHoldAndItsDerivativeIsItsRate) {
  for (const double c : {0.0, 0.1, 2.0, 10.0}) {
    for (const double k : {0.0, 1e-4, 1.0}) {
      if (c == 0.0 && k == 0.0) continue;  // polynomial: bounded by its horizon only (tested by the runs)
      Forcing load;
      load.f0 = 0.5;
      load.n = 1;
      load.w[0] = 1.3;
      load.fs[0] = 0.8;
      Wave w;
      event_driven::general_oscillator_into(w, 0.0, 0.1, 0.2, 1.0, c, k, load, 30.0);
      const Wave dw = event_driven::derivative(w);
      for (double t : {0.0, 0.5, 3.0, 9.0}) {
        double b[event_driven::kMaxDerivative + 1];
        for (int d = 0; d <= event_driven::kMaxDerivative; ++d) b[d] = w.bound(t, d);
        for (double s = t; s <= 30.0; s += 0.01) {
          double v[event_driven::kMaxDerivative + 1], dv[2];
          w.eval(s, v, event_driven::kMaxDerivative + 1);
          dw.eval(s, dv, 2);
          const std::string what = "c=" + std::to_string(c) + " k=" + std::to_string(k) + " t=" + std::to_string(t);
          ASSERT_LE(std::abs(v[0] - w.mean()), b[0] * (1 + 1e-12) + 1e-12) << what << " s=" << s;
          for (int d = 1; d <= event_driven::kMaxDerivative; ++d)
            ASSERT_LE(std::abs(v[d]), b[d] * (1 + 1e-12) + 1e-12) << what << " d=" << d << " s=" << s;
          ASSERT_NEAR(dv[0], v[1], 1e-12 * (1 + std::abs(v[1]))) << what << " s=" << s;
          ASSERT_NEAR(dv[1], v[2], 1e-12 * (1 + std::abs(v[2]))) << what << " s=" << s;
        }
      }
    }
  }
}

// The cases the energy and self-similarity tests run: every scene, both pulses and
// directivities, alpha 0 (elastic-perfectly plastic), 0.05, 0.2, undamped bodies, and
// touching bodies (persistent contact between a yielding and an elastic body).
std::vector<Case> yielding_cases() {
  std::vector<Case> out;
  for (Scene scene : {Scene::wall, Scene::pair, Scene::row3, Scene::chain})
    for (PulseShape pulse : {PulseShape::sine, PulseShape::cosine})
      for (double alpha : {0.0, 0.05, 0.2})
        for (double pi2 : {0.4, 1.0, 2.5}) {
          Case c = test::yielding_case(scene, pulse, pi2, scene == Scene::chain ? 1.0 : 0.5, 0.5, 0.4, alpha);
          if (pi2 == 2.5) c.directivity = Directivity::reverse;
          out.push_back(c);
        }
  Case undamped = test::yielding_case(Scene::pair, PulseShape::sine, 1.0, 0.5, 0.5, 0.3, 0.0);
  undamped.xi = 0.0;
  out.push_back(undamped);
  Case touching = test::yielding_case(Scene::pair, PulseShape::cosine, 0.8, 2.0, 0.0, 0.3, 0.05);
  touching.pi3 = 0.0;
  touching.pi_y1 = kInf;
  out.push_back(touching);
  Case plastic_row = test::yielding_case(Scene::row3, PulseShape::sine, 1.5, 0.5, 0.0, 0.2, 0.0);
  plastic_row.pi3 = 0.05;
  out.push_back(plastic_row);
  // The other loads (cases/load.hpp): a pulse model's sinusoids, and a record's linear
  // pieces (the general mode's ramp), one event per sample.
  for (PulseShape pulse : {PulseShape::makris_c, PulseShape::mp}) {
    Case c = test::yielding_case(Scene::pair, pulse, 1.0, 0.5, 0.5, 0.3, 0.05);
    if (pulse == PulseShape::makris_c) c.cycles = 2;
    if (pulse == PulseShape::mp) {
      c.mp_gamma = 2.0;
      c.mp_nu = 30.0;
    }
    out.push_back(c);
  }
  for (double alpha : {0.0, 0.2}) {
    Case c = test::yielding_case(Scene::pair, PulseShape::record, 1.0, 0.5, 0.5, 0.3, alpha);
    c.samples = read_record(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/records/mp-noise-20s.csv");
    c.record = "mp-noise-20s.csv";
    c.a_p = c.samples->peak;
    c.w_p = std::numbers::pi;  // tp = 2 s
    c.n_free = 1.0;
    out.push_back(c);
  }
  return out;
}

std::string label(const Case& c) {
  return std::string(name(c.scene)) + " " + std::string(name(c.pulse)) + " " + std::string(name(c.directivity)) +
         " pi2=" + std::to_string(c.pi2) + " alpha=" + std::to_string(c.alpha) + " xi=" + std::to_string(c.xi) +
         " pi3=" + std::to_string(c.pi3);
}

// With a yield displacement no motion reaches (Pi_y 1e6), every row is today's elastic
// answer to the last bit: the same waves, events and impacts; only the energy is summed
// with the hysteretic variables, which equal the displacements.
TEST(YieldingReference, AFarYieldIsTheElasticAnswerBitForBit) {
  for (Scene scene : {Scene::wall, Scene::pair, Scene::row3, Scene::chain})
    for (PulseShape pulse : {PulseShape::sine, PulseShape::cosine, PulseShape::makris_c})
      for (double pi2 : {0.3, 1.0, 3.0}) {
        Case elastic = test::make_case(scene, pulse, pi2, 0.5, 0.5);
        if (pulse == PulseShape::makris_c) elastic.cycles = 2;
        if (scene == Scene::chain) elastic.bodies = 5;
        Case far = elastic;
        if (scene == Scene::chain) {
          far.pi_y = 1e6;
        } else {
          far.pi_y0 = 1e6;
          if (scene != Scene::wall) far.pi_y1 = 1e6;
          if (scene == Scene::row3) far.pi_y2 = 1e6;
        }
        far.alpha = 0.05;
        // A chain of yielding bodies is solved eagerly (every body advanced and the frame
        // rebuilt at every event), an elastic one lazily (DERIVATION.md §9): the same answer
        // to round-off, the eager one's to the bit.
        const auto elastic_solve =
            scene == Scene::chain ? event_driven::detail::solve_rebuilding_every_body : event_driven::solve;
        const Result a = elastic_solve(make_system(elastic), {});
        const Result b = event_driven::solve(make_system(far), {});
        const std::string what = label(elastic);
        ASSERT_EQ(a.status, Status::ok) << what;
        ASSERT_EQ(b.status, Status::ok) << what;
        EXPECT_EQ(a.pi1, b.pi1) << what;
        EXPECT_EQ(a.t_max, b.t_max) << what;
        EXPECT_EQ(a.impacts, b.impacts) << what;
        EXPECT_EQ(a.steps, b.steps) << what;
        EXPECT_EQ(b.residual, 0.0) << what;
        EXPECT_EQ(b.energies.hysteretic, 0.0) << what;
        EXPECT_TRUE(std::isnan(a.residual)) << what;
      }
}

// Self-similarity (cases/README.md): the same Pi terms at other a_p, w_p give the same Pi1,
// residual and hysteretic share. The reference's tolerances are relative to the pulse's
// scales, so only round-off differs: 1e-12 (measured 5e-15 at most).
TEST(YieldingReference, YieldingIsSelfSimilarAcrossThePulsesScale) {
  double worst = 0.0;
  for (const Case& base : yielding_cases()) {
    const Result a = event_driven::solve(make_system(base), {});
    ASSERT_EQ(a.status, Status::ok) << label(base) << ": " << a.message;
    for (const auto& [a_p, w_p] : {std::pair{9.81, 6.283185307179586}, std::pair{0.02, 0.3}}) {
      Case scaled = base;
      if (base.pulse == PulseShape::record) continue;  // a record has its own time and units
      scaled.a_p = a_p;
      scaled.w_p = w_p;
      const Result b = event_driven::solve(make_system(scaled), {});
      ASSERT_EQ(b.status, Status::ok) << label(scaled) << ": " << b.message;
      const auto rel = [](double x, double y) { return std::abs(x - y) / std::max(1.0, std::abs(x)); };
      worst = std::max({worst, rel(a.pi1, b.pi1), rel(a.residual, b.residual), rel(a.hysteretic, b.hysteretic)});
      EXPECT_LT(rel(a.pi1, b.pi1), 1e-12) << label(base) << " a_p=" << a_p;
      EXPECT_LT(rel(a.residual, b.residual), 1e-12) << label(base) << " a_p=" << a_p;
      EXPECT_LT(rel(a.hysteretic, b.hysteretic), 1e-12) << label(base) << " a_p=" << a_p;
    }
  }
  RecordProperty("worst", test::sci(worst));
}

// The ground's work is what the bodies hold at t_end plus what the dampers, the hysteresis
// and the impacts took: 1e-9 of the input (measured below 1e-12; a wrong branch offset or
// stiffness breaks it at 1e-2).
TEST(YieldingReference, EnergyBalanceClosesWithTheHystereticTerm) {
  double worst = 0.0;
  int yielded = 0;
  for (const Case& c : yielding_cases()) {
    const Result r = event_driven::solve(make_system(c), {});
    ASSERT_EQ(r.status, Status::ok) << label(c) << ": " << r.message;
    const Result::Energies& e = r.energies;
    const double held = e.kinetic + e.elastic + e.damped + e.hysteretic + e.impacts;
    const double gap = std::abs(e.input - held) / e.input;
    worst = std::max(worst, gap);
    EXPECT_LT(gap, 1e-9) << label(c) << ": input " << e.input << ", held " << held;
    EXPECT_GE(e.hysteretic, 0.0) << label(c);
    EXPECT_GE(e.impacts, -1e-12 * e.input) << label(c);
    yielded += e.hysteretic > 0.0 ? 1 : 0;
  }
  EXPECT_GT(yielded, 50);  // the cases do yield
  RecordProperty("worst", test::sci(worst));
}

// An elastic-perfectly plastic body under a one-sided push that it cannot resist drifts and
// stays: its residual is where it came to rest, and a body that never yields has none.
TEST(YieldingReference, ResidualIsTheRestPositionOfTheLastElasticBranch) {
  Case c;
  c.scene = Scene::wall;
  c.pulse = PulseShape::sine;
  c.directivity = Directivity::reverse;  // away from the wall
  c.pi2 = 1.0;
  c.pi3 = 100.0;  // the wall is never reached
  c.eps = 0.5;
  c.pi_y0 = 0.2;
  c.alpha = 0.0;
  c.n_free = 20.0;  // long enough for the motion to die out
  const System s = make_system(c);
  Settings settings;
  settings.history_samples = 2;
  const Result r = event_driven::solve(s, settings);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  const double u_end = r.history.data[static_cast<std::size_t>(r.history.row_size()) + 1];
  EXPECT_GT(std::abs(r.residual), 0.5);  // a plastic drift of several yield displacements
  // After 20 periods at 5 % damping the elastic oscillation is below 2e-3 of its start: the
  // body sits at its residual to that.
  EXPECT_NEAR(u_end / s.length_scale(), r.residual, 2e-3 * std::abs(r.residual));
}

}  // namespace yielding_reference_tests
}  // namespace pb
