// The reference's root and peak polish (solvers/event_driven/search.cpp) against the
// bisection it replaced, kept here as the oracle: on many random gap and body waves (plain,
// near-resonant, under a linear load) a Newton-polished root is the first double of a sign
// change of the rounded wave, within the old root's stopping width and the wave's rounding
// band (4 eps of its terms over its slope) of the old one;
// a polished peak's value is the old one's to the wave's rounding.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "solvers/event_driven/search.hpp"
#include "solvers/event_driven/wave.hpp"

namespace pb::event_driven {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace search_tests {

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct P {
  double t, f, df;
};

P at(const Wave& w, double t) {
  double v[2];
  w.eval(t, v, 2);
  return {t, v[0], v[1]};
}

// search.cpp's refine_root before issue 23: Newton from the end of smaller |f|, bisection
// when it leaves the bracket, down to a bracket of 2 eps |t|; its hi end.
double old_refine_root(const Wave& g, P lo, P hi) {
  double t = hi.t;
  for (int it = 0; it < 100 && hi.t - lo.t > 2.0 * kEps * std::abs(hi.t); ++it) {
    const P& p = std::abs(lo.f) < std::abs(hi.f) ? lo : hi;
    double next = p.df != 0.0 ? p.t - p.f / p.df : 0.5 * (lo.t + hi.t);
    if (!(next > lo.t && next < hi.t)) next = 0.5 * (lo.t + hi.t);
    const P q = at(g, next);
    if (q.f > 0.0)
      lo = q;
    else
      hi = q;
    t = hi.t;
    if (q.f == 0.0) break;
  }
  return t;
}

// search.cpp's stationary before issue 23.
P old_stationary(const Wave& f, P a, P b) {
  for (int it = 0; it < 100 && b.t - a.t > 2.0 * kEps * std::abs(b.t); ++it) {
    double v[3];
    const double mid = 0.5 * (a.t + b.t);
    f.eval(mid, v, 3);
    double next = v[2] != 0.0 ? mid - v[1] / v[2] : mid;
    if (!(next > a.t && next < b.t)) next = mid;
    const P q = at(f, next);
    if ((q.df > 0.0) == (a.df > 0.0))
      a = q;
    else
      b = q;
    if (q.df == 0.0) return q;
  }
  return std::abs(a.df) < std::abs(b.df) ? a : b;
}

// A random body motion from t0: plain forcing, near resonance (R_mj), or a linear load
// with two sinusoids (a record's or a pulse model's piece).
Wave random_body(std::mt19937_64& rng, double t0, int kind) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.2, 3.0), xi(0.0, 0.15);
  const double m = pos(rng), w = pos(rng), c = 2.0 * xi(rng) * w * m, k = m * w * w;
  const double x0 = 0.3 * u(rng), v0 = 0.3 * u(rng);
  const double horizon = t0 + 20.0;
  if (kind == 2) {
    Forcing load;
    load.f0 = 0.2 * u(rng);
    load.f1 = 0.05 * u(rng);
    load.n = 2;
    load.w = {pos(rng), pos(rng), 0.0};
    load.fs = {u(rng), u(rng), 0.0};
    load.fc = {u(rng), u(rng), 0.0};
    return oscillator(t0, x0, v0, m, c, k, load, horizon);
  }
  const double wp = kind == 1 ? w * (1.0 + 0.002 * u(rng)) : pos(rng);
  const double cc = kind == 1 ? 1e-4 * c : c;  // near resonance needs sigma well below kNearResonance w
  return oscillator(t0, x0, v0, m, cc, k, 0.1 * u(rng), u(rng), u(rng), wp, horizon);
}

// add_scaled matches sinusoids by frequency, up to kMaxSines: a record's piece (two
// sinusoids) gives both bodies of a gap its frequencies, as the gaps below need.
Wave same_load(Wave body, const Wave& other) {
  if (body.lin == 0.0 && other.lin == 0.0) return body;
  body.sine = other.sine;
  body.lin = other.lin;
  body.prepare();
  return body;
}

// g, already the constant 0 from the bodies' t0, made the gap right - left_scale left with
// value f0 there, prepared.
void write_gap(Wave& g, const Wave& right, const Wave& left, double left_scale, double f0) {
  add_scaled(g, right, 1.0);
  add_scaled(g, left, -left_scale);
  g.f0 = f0;
  g.prepare();
}

// The gap between two random bodies of one kind (both have the load's frequencies then).
Wave random_gap(std::mt19937_64& rng, double t0, int kind) {
  std::uniform_real_distribution<double> gap(0.0, 0.2);
  const Wave right = random_body(rng, t0, kind), left = same_load(random_body(rng, t0, kind), right);
  Wave g = constant(t0, 0.0);
  write_gap(g, right, left, 1.0, gap(rng));
  return g;
}

TEST(SearchPolish, NewtonPolishedRootsAreTheOldBisectionRootsToItsStoppingWidth) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> start(0.0, 50.0);
  int roots = 0, same = 0, earlier = 0;
  double worst = 0.0;
  for (int n = 0; n < 3000 && roots < 2000; ++n) {
    const int kind = n % 3;
    const double t0 = n % 2 ? start(rng) : 0.0;  // large t too: ulps of t grow
    const Wave g = random_gap(rng, t0, kind);
    // The first grid interval of 1/200 of the fastest period where g falls through zero.
    const double dt = 0.01;
    P a = at(g, t0);
    for (double t = t0 + dt; t < t0 + 20.0; t += dt) {
      const P b = at(g, t);
      if (a.f > 0.0 && b.f <= 0.0 && a.df < 0.0 && b.df < 0.0) {
        const double fresh = detail::polish_root(g, a.t, b.t), old = old_refine_root(g, a, b);
        ASSERT_GT(fresh, a.t);
        ASSERT_LE(fresh, b.t);
        EXPECT_LE(g.value(fresh), 0.0) << n;
        EXPECT_GT(g.value(std::nextafter(fresh, -1.0)), 0.0) << n;
        // g is known to its rounding, 4 eps of its terms (its constant and the size of its
        // oscillation), so its sign may change several times within 4 eps S / |g'| of the
        // root: each search may stop at any of those changes, and the old one also up to its
        // stopping width 2 eps |t| after it.
        const double band = 4.0 * kEps * (std::abs(g.f0) + g.bound(t0, 0)) / std::abs(at(g, fresh).df);
        EXPECT_LE(std::abs(fresh - old), 2.0 * kEps * std::abs(old) + band) << n << ": " << fresh << " vs " << old;
        worst = std::max(worst, std::abs(fresh - old) / (2.0 * kEps * std::abs(old) + band));
        same += fresh == old;
        earlier += fresh < old;
        ++roots;
        break;
      }
      a = b;
    }
  }
  EXPECT_GE(roots, 1000);
  ::testing::Test::RecordProperty("roots", std::to_string(roots));
  ::testing::Test::RecordProperty("bit_for_bit", std::to_string(same));
  ::testing::Test::RecordProperty("earlier", std::to_string(earlier));
  ::testing::Test::RecordProperty("worst_over_bound", std::to_string(worst));
}

TEST(SearchPolish, PolishedPeaksHaveTheOldPeaksValueToTheWavesRounding) {
  std::mt19937_64 rng(2023);
  std::uniform_real_distribution<double> start(0.0, 50.0);
  int peaks = 0, same = 0;
  for (int n = 0; n < 3000 && peaks < 2000; ++n) {
    const int kind = n % 3;
    const double t0 = n % 2 ? start(rng) : 0.0;
    const Wave f = random_body(rng, t0, kind);
    // Rounding scale of f: its constant and its oscillation's size.
    const double scale = std::abs(f.f0) + f.bound(t0, 0);
    const double dt = 0.01;
    double va[3], vb[3];
    f.eval(t0 + dt, va, 3);
    for (double t = t0 + 2.0 * dt; t < t0 + 20.0; t += dt) {
      f.eval(t, vb, 3);
      if ((va[1] > 0.0) != (vb[1] > 0.0) && (va[2] > 0.0) == (vb[2] > 0.0) && va[2] != 0.0) {
        const Peak fresh = detail::polish_stationary(f, t - dt, t);
        const P old = old_stationary(f, {t - dt, va[0], va[1]}, {t, vb[0], vb[1]});
        EXPECT_LE(std::abs(fresh.value - std::abs(old.f)), 4.0 * kEps * scale) << n;
        EXPECT_LE(std::abs(fresh.t - old.t), 1e-6 * dt) << n;  // f' is flat to rounding there
        same += fresh.value == std::abs(old.f);
        ++peaks;
        break;
      }
      std::copy(vb, vb + 3, va);
    }
  }
  EXPECT_GE(peaks, 1000);
  ::testing::Test::RecordProperty("peaks", std::to_string(peaks));
  ::testing::Test::RecordProperty("bit_for_bit", std::to_string(same));
}

// The whole first-root search (windows, their one-sign tests from both ends, the Taylor
// reach that skips a just-opened gap's first windows) against a scan of 1/100 s: it never
// ends after the scan's first crossing, and what it returns is a crossing.
TEST(SearchFirstRoot, NeverLaterThanADenseScanOnRandomGapsIncludingJustOpenedOnes) {
  std::mt19937_64 rng(7);
  Deadline never{Settings{}};
  int compared = 0, found = 0;
  for (int n = 0; n < 1500; ++n) {
    const int kind = n % 3;
    Wave g = random_gap(rng, 0.0, kind);
    if (n % 2) {
      // Just opened: zero gap, opening.
      g.f0 = 0.0;
      if (at(g, 0.0).df < 0.0) {
        Wave flipped = constant(0.0, 0.0);
        add_scaled(flipped, g, -1.0);
        flipped.prepare();
        g = flipped;
      }
    }
    const double end = 20.0, floor = 1e-13, settle = 1e-4, noise = 1e-12;
    const double r = first_root(g, 0.0, end, floor, settle, noise, never);
    double scan = std::numeric_limits<double>::quiet_NaN();
    for (double t = 0.01; t <= end; t += 0.01)
      if (g.value(t) <= 0.0) {
        scan = t;
        break;
      }
    if (!std::isnan(r)) {
      ++found;
      EXPECT_LE(g.value(r), 0.0) << n;
      if (r > 0.0) {
        EXPECT_GT(g.value(std::nextafter(r, 0.0)), 0.0) << n;
      }
    }
    if (!std::isnan(scan)) {
      ++compared;
      ASSERT_FALSE(std::isnan(r)) << n << ": the scan crosses at " << scan;
      EXPECT_LE(r, scan) << n;
    }
  }
  EXPECT_GE(compared, 500);
  ::testing::Test::RecordProperty("compared", std::to_string(compared));
  ::testing::Test::RecordProperty("found", std::to_string(found));
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }


// Where the state is advanced, every wave of a frame is evaluated at one t through one
// TrigCache: its values must be eval()'s bit for bit (the reference's results rest on it).
// Waves of all three kinds, from one t0, several sharing their modes (a gap and its
// bodies), at t = t0 (eval's shortcut) and after.
TEST(WaveEval, ATrigCacheAtOneTGivesPlainEvalsValuesBitForBit) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> later(0.0, 15.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int kind = trial % 3;
    const double t0 = 0.5 * trial;
    const Wave right = random_body(rng, t0, kind), left = same_load(random_body(rng, t0, kind), right);
    Wave g = constant(t0, 0.0);
    write_gap(g, right, left, 1.0, 0.1);
    for (const double t : {t0, t0 + later(rng), t0 + later(rng)}) {
      TrigCache trig;
      for (int pass = 0; pass < 2; ++pass) {  // the second pass hits the cache throughout
        for (const Wave* w : {&right, &left, static_cast<const Wave*>(&g)}) {
          double plain[kMaxDerivative + 1], cached[kMaxDerivative + 1];
          w->eval(t, plain, kMaxDerivative + 1);
          w->eval(t, cached, kMaxDerivative + 1, trig);
          for (int d = 0; d <= kMaxDerivative; ++d)
            ASSERT_TRUE(same_bits(plain[d], cached[d])) << trial << " d " << d << ": " << plain[d] << " " << cached[d];
        }
      }
    }
  }
}

// A gap rebuilt in place (reset(), as build_frame does at each event) over a wave that held
// other modes and sinusoids is the gap built from constant(), value for value.
TEST(WaveEval, AResetWaveIsTheFreshOne) {
  std::mt19937_64 rng(5);
  Wave reused = random_gap(rng, 0.0, 2);
  for (int trial = 0; trial < 100; ++trial) {
    const int kind = trial % 3;
    const double t0 = 0.25 * trial;
    const Wave right = random_body(rng, t0, kind), left = same_load(random_body(rng, t0, kind), right);
    Wave fresh = constant(t0, 0.0);
    reset(reused, t0, 0.0);
    for (Wave* g : {&fresh, &reused}) write_gap(*g, right, left, 0.5, 0.05);
    for (double t = t0; t < t0 + 10.0; t += 0.37) {
      double a[kMaxDerivative + 1], b[kMaxDerivative + 1];
      fresh.eval(t, a, kMaxDerivative + 1);
      reused.eval(t, b, kMaxDerivative + 1);
      for (int d = 0; d <= kMaxDerivative; ++d) ASSERT_TRUE(same_bits(a[d], b[d])) << trial << " " << t << " " << d;
      for (int d = 0; d <= kMaxDerivative; ++d) ASSERT_TRUE(same_bits(fresh.bound(t, d), reused.bound(t, d)));
    }
    ASSERT_TRUE(same_bits(fresh.mean(), reused.mean()));
  }
}

// A body's wave written in place over a used one (build_frame's free bodies) is the
// returned one, value for value: plain, near-resonant, and a record's piece.
TEST(WaveEval, AnOscillatorWrittenInPlaceIsTheReturnedOne) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.2, 3.0), xi(0.0, 0.15);
  Wave reused = random_gap(rng, 0.0, 2);
  for (int trial = 0; trial < 150; ++trial) {
    const int kind = trial % 3;
    const double t0 = 0.3 * trial, m = pos(rng), w = pos(rng), k = m * w * w, x0 = 0.3 * u(rng), v0 = 0.3 * u(rng);
    const double c = kind == 1 ? 1e-4 * 2.0 * xi(rng) * w * m : 2.0 * xi(rng) * w * m;
    Wave fresh;
    if (kind == 2) {
      Forcing load;
      load.f0 = 0.2 * u(rng);
      load.f1 = 0.05 * u(rng);
      load.n = 2;
      load.w = {pos(rng), w * (1.0 + 0.001 * u(rng)), 0.0};
      load.fs = {u(rng), u(rng), 0.0};
      load.fc = {u(rng), u(rng), 0.0};
      fresh = oscillator(t0, x0, v0, m, c, k, load, t0 + 20.0);
      oscillator_into(reused, t0, x0, v0, m, c, k, load, t0 + 20.0);
    } else {
      const double wp = kind == 1 ? w * (1.0 + 0.002 * u(rng)) : pos(rng), f = 0.1 * u(rng), fs = u(rng), fc = u(rng);
      fresh = oscillator(t0, x0, v0, m, c, k, f, fs, fc, wp, t0 + 20.0);
      oscillator_into(reused, t0, x0, v0, m, c, k, f, fs, fc, wp, t0 + 20.0);
    }
    for (double t = t0; t < t0 + 10.0; t += 0.41) {
      double a[kMaxDerivative + 1], b[kMaxDerivative + 1];
      fresh.eval(t, a, kMaxDerivative + 1);
      reused.eval(t, b, kMaxDerivative + 1);
      for (int d = 0; d <= kMaxDerivative; ++d) {
        ASSERT_TRUE(same_bits(a[d], b[d])) << trial << " " << t << " " << d;
        ASSERT_TRUE(same_bits(fresh.bound(t, d), reused.bound(t, d))) << trial << " " << t << " " << d;
      }
    }
    ASSERT_TRUE(same_bits(fresh.mean(), reused.mean()));
    ASSERT_EQ(fresh.any_resonant, reused.any_resonant);
  }
}

// A dip that reaches 1e-10 of the gap below zero is a root, whether the gap starts by
// closing or by opening: the skips never step over a grazing approach. One that stays as
// far above zero is none.
// The whole peak search (windows, their exclusion by the interpolant's error, which vanishes
// at a window's ends, the stationary polish) against a scan of 1/200 s: the largest |f| it
// returns is a value of f, and no scanned value is larger beyond f's rounding. Half the
// waves start from rest under their load (f, f' and, for a sine, f'' zero at t0), where
// every window ends on a new largest |f|.
TEST(SearchPeak, NoScannedValueAboveTheFoundPeakAlsoFromRest) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.2, 3.0), xi(0.0, 0.15);
  Deadline never{Settings{}};
  for (int n = 0; n < 600; ++n) {
    Wave f;
    if (n % 2) {
      f = random_body(rng, 0.0, n % 3);
    } else {
      const double m = pos(rng), w = pos(rng), k = m * w * w, c = 2.0 * xi(rng) * w * m;
      const double fs = n % 4 ? u(rng) : 0.0, fc = n % 4 ? 0.0 : u(rng);  // one-sine or one-cosine
      f = oscillator(0.0, 0.0, 0.0, m, c, k, 0.0, fs, fc, pos(rng), 20.0);
    }
    const double end = 10.0;
    Peak peak;
    max_abs(f, 0.0, end, 1e-13, peak, never);
    ASSERT_EQ(peak.value, std::abs(f.value(peak.t))) << n;
    const double rounding = 4.0 * kEps * (std::abs(f.f0) + f.bound(0.0, 0));
    for (double t = 0.0; t <= end; t += 0.005)
      EXPECT_LE(std::abs(f.value(t)), peak.value + rounding) << n << " at " << t;
  }
}

TEST(SearchFirstRoot, AGrazingDipIsFoundAndANearMissIsNot) {
  Deadline never{Settings{}};
  const double f0 = 1e-3;
  for (double depth : {1e-10, -1e-10}) {
    for (double opening : {0.0, 1e-3, -1e-3}) {
      // f = f0 + a (cos t - 1) + b sin t, whose least value is f0 - a - hypot(a, b).
      const double least = -depth * f0, c = f0 - least, b = opening;
      Wave g = constant(0.0, f0);
      g.n_modes = 1;
      g.mode[0].omega = 1.0;
      g.mode[0].a = (c * c - b * b) / (2.0 * c);
      g.mode[0].b = b;
      g.prepare();
      const double r = first_root(g, 0.0, 10.0, 1e-13, 1e-4, 1e-15, never);
      if (depth > 0.0) {
        ASSERT_FALSE(std::isnan(r)) << depth << " " << opening;
        EXPECT_LE(g.value(r), 0.0);
        EXPECT_GT(g.value(std::nextafter(r, 0.0)), 0.0) << opening << ": " << r;
      } else {
        EXPECT_TRUE(std::isnan(r)) << depth << " " << opening << ": " << r;
      }
    }
  }
}

// Issue 32: an undamped oscillator from rest at 4 times the sine load's frequency. Its free
// term's amplitude is the forced one's over 4, exactly in binary, so near t0 the two sines
// cancel to exact zeros (up to t ~ 5e-9): the peak search marched and halved that plateau
// at its floor, some 66 000 windows against its neighbours' 32 and 40. Now 62 (the
// neighbours 32 and 66: 4 - 5e-5 has a shorter plateau of its own). The budget, 4 times the
// neighbours' windows, is a thousandth of the plateau's count.
TEST(SearchPeak, AWaveOfExactZerosAtItsStartCostsWhatItsNeighboursCost) {
  const double floor = 1e-13 * 2.0 * std::acos(-1.0) / 4.0;  // the reference's, for t_min = 2 pi / 4
  const auto search = [&](double w0, long& windows) {
    const Wave f = oscillator(0.0, 0.0, 0.0, 1.0, 0.0, w0 * w0, 0.0, -1.0, 0.0, 1.0, 2.0 * std::acos(-1.0));
    Deadline counted{Settings{}};
    Peak peak;
    max_abs(f, 0.0, 4.7, floor, peak, counted);
    windows = counted.ticks();
    return peak.value;
  };
  long below = 0, at = 0, above = 0;
  const double delta = 5e-5;
  const double p_below = search(4.0 - delta, below), p_at = search(4.0, at), p_above = search(4.0 + delta, above);
  EXPECT_LE(at, 4 * std::max(below, above)) << "neighbours " << below << ", " << above;
  // The peak is smooth in w0: the neighbours' mean is its value to O(delta^2) (measured
  // differences of 1e-9 at delta = 5e-5; 1e-8 leaves room).
  EXPECT_NEAR(p_at, 0.5 * (p_below + p_above), 1e-8 * p_at);
}

}  // namespace search_tests
}  // namespace pb::event_driven
