// The loads beyond the paper's pulses (issue 21): records and the pulse models, as cases/
// reads and builds them (cases/record.hpp, cases/load.hpp), and the reference's closed form
// for them (DERIVATION.md §1) against independent solutions:
//   - a record that samples the sine pulse converges to the sine pulse's reference at the
//     order of linear interpolation (second);
//   - a ramp record follows the motion derived by hand;
//   - makris-a and makris-b, through the general path, are the sine and cosine pulses;
//   - the pulse models end at rest, and the mp acceleration is its velocity's derivative.
// (Against CVODE at a tight tolerance: solvers/compliant/loads_cvode_test.cpp.)

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "cases/case_set.hpp"
#include "cases/load.hpp"
#include "cases/record.hpp"
#include "cases/system.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "kit/testing.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace loads_tests {

using test::sci;

const std::string kRecords = std::string(POUNDBENCH_SOURCE_DIR) + "/cases/records/";

using test::record_error;

// ---------------------------------------------------------------- reading

// The AT2 file holds the CSV's values in g with 8 significant digits ("%15.7E"), at t = i DT.
TEST(Records, AnAt2FileAndItsCsvTwinAgreeToTheAt2sDigits) {
  for (const char* name : {"mp-noise-20s", "mp-noise-40s"}) {
    const auto csv = read_record(kRecords + name + ".csv");
    const auto at2 = read_record(kRecords + name + ".at2");
    ASSERT_EQ(csv->t.size(), at2->t.size()) << name;
    double dt = 0.0, da = 0.0;
    for (std::size_t i = 0; i < csv->t.size(); ++i) {
      dt = std::max(dt, std::abs(csv->t[i] - at2->t[i]));
      da = std::max(da, std::abs(csv->a[i] - at2->a[i]));
    }
    // Times: the CSV's 10 digits of i DT. Values: half a unit of the 8th digit of a value
    // below the peak, 5e-8 of the peak (measured 4e-8).
    EXPECT_LT(dt, 1e-9) << name;
    EXPECT_LT(da, 5e-8 * csv->peak) << name << ": " << sci(da / csv->peak) << " of the peak";
    EXPECT_NEAR(at2->peak, csv->peak, 5e-8 * csv->peak) << name;
  }
}

TEST(Records, EveryBadRecordIsRefusedNamingTheFileAndLine) {
  struct Bad {
    const char* text;
    const char* source;
    const char* expected;  // the start of the message
  };
  const std::vector<Bad> bad = {
      {"t,a\n0,1\n0.2,2\n0.1,3\n", "x.csv", "x.csv:4: t: goes back"},
      {"0,1\n0.1,2\n0.1,3\n", "x.csv", "x.csv:3: t: repeats"},
      {"0,1\n0.1,abc\n", "x.csv", "x.csv:2: a_g: not a number (\"abc\")"},
      {"0,1\nzero,2\n", "x.csv", "x.csv:2: t: not a number"},
      {"0,1\n0.1\n", "x.csv", "x.csv:2: expected two columns"},
      {"0,1\n0.1,2,3\n", "x.csv", "x.csv:2: expected two columns"},
      {"0,1\n0.1,nan\n", "x.csv", "x.csv:2: a_g: must be finite"},
      {"-0.1,1\n0.1,2\n", "x.csv", "x.csv:1: t: must be finite and >= 0"},
      {"", "x.csv", "x.csv:1: no samples"},
      {"# only a comment\n\n", "x.csv", "x.csv:1: no samples"},
      {"0,1\n", "x.csv", "x.csv:1: one sample"},
      {"0,0\n1,0\n", "x.csv", "x.csv: every acceleration is zero"},
      {"h\nh\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 3, DT= .01 SEC\n 1 2\n", "x.AT2",
       "x.AT2:4: NPTS = 3, but the file holds 2 values"},
      {"h\nh\nUNITS OF G\nNPTS= 2, DT= .01 SEC\n 1 2\n 3\n", "x.at2", "x.at2:6: more values than NPTS = 2"},
      {"h\nh\nUNITS OF G\nNPTS= 2, DT= .01 SEC\n 1 x2\n", "x.at2", "x.at2:5: value 2: not a number (\"x2\")"},
      {"h\nh\nUNITS OF G\nNPTS= 2.5, DT= .01 SEC\n 1 2\n", "x.at2", "x.at2:4: NPTS: not a whole number"},
      {"h\nh\nUNITS OF G\nNPTS= 2, DT= 0 SEC\n 1 2\n", "x.at2", "x.at2:4: DT: not a positive time step"},
      {"h\nh\nVELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS= 2, DT= .01 SEC\n 1 2\n", "x.at2", "x.at2:3: units"},
      {"h\nh\n", "x.at2", "x.at2: no NPTS/DT line"},
  };
  for (const Bad& b : bad) EXPECT_EQ(record_error(b.text, b.source).rfind(b.expected, 0), 0u) << record_error(b.text, b.source);
}

TEST(Records, Both4thLineFormsOfAnAt2FileReadTheSame) {
  const Record a = parse_record("h\nh\nUNITS OF G\nNPTS=    3, DT=   .0200 SEC,\n .1E+00 -.2E+00\n 3.D-01\n", "a.at2");
  const Record b = parse_record("h\nh\nUNITS OF G\n    3    .0200    NPTS, DT\n .1E+00 -.2E+00 3.E-01\n", "b.AT2");
  ASSERT_EQ(a.t.size(), 3u);
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.a, b.a);
  EXPECT_DOUBLE_EQ(a.t[2], 0.04);
  EXPECT_DOUBLE_EQ(a.a[1], -0.2 * kStandardGravity);  // values in g
}

// ---------------------------------------------------------------- the load interface

Case record_case(std::shared_ptr<const Record> r, double a_p, double w_p) {
  Case c = test::make_case(Scene::pair, PulseShape::record, 1.0, 0.5, 0.5);
  c.samples = std::move(r);
  c.record = "(in memory)";
  c.a_p = a_p;
  c.w_p = w_p;
  return c;
}

// A cursor's answers are Pulse's (binary search) bit for bit, forward, backward and by jumps;
// the step mean is the integral of the linear interpolation (checked against the midpoint rule
// on each part between samples, exact for a linear function: to 1e-13 of the peak).
// The mean period of Rathje, Abrahamson & Bray (1998), cases/record.hpp. A pure harmonic's is
// its period, lifted by the leakage of a finite record through the 1/f weight: over 20 s at
// 0.01 s, measured 1.2 %, 0.9 % and 0.5 % above 1/f0 at 1, 2 and 5 Hz (cases/README.md quotes
// 2 Hz); 2 % allows it. Two harmonics weigh their periods by their squared amplitudes (the
// same leakage: measured 1.5 % above, 3 % allowed). Samples at an uneven spacing are taken on
// an even grid, linear between them: the same T_m to the interpolation's error (measured
// 1.2e-3 relative; 1e-2 allowed).
TEST(Records, TheMeanPeriodIsAHarmonicsPeriodAndWeighsTwoBySquaredAmplitude) {
  const auto sampled = [](double dt, double jitter, auto&& a_of) {
    std::vector<double> t, a;
    for (int i = 0; i * dt <= 20.0 + 1e-9; ++i) {
      t.push_back(i * dt + (i % 2 ? jitter * dt : 0.0));
      a.push_back(a_of(t.back()));
    }
    return std::pair{t, a};
  };
  for (double f0 : {1.0, 2.0, 5.0}) {
    const auto [t, a] = sampled(0.01, 0.0, [&](double s) { return std::sin(2.0 * std::numbers::pi * f0 * s); });
    const double t_m = mean_period(t, a);
    EXPECT_GE(t_m, 1.0 / f0) << f0;
    EXPECT_LT(t_m, 1.02 / f0) << f0;
  }
  const auto two = [](double s) {
    return 2.0 * std::sin(2.0 * std::numbers::pi * 1.0 * s) + std::sin(2.0 * std::numbers::pi * 4.0 * s);
  };
  const auto [t2, a2] = sampled(0.01, 0.0, two);
  const double expected = (4.0 / 1.0 + 1.0 / 4.0) / (4.0 + 1.0);
  EXPECT_NEAR(mean_period(t2, a2), expected, 0.03 * expected);
  const auto [tj, aj] = sampled(0.01, 0.3, two);
  EXPECT_NEAR(mean_period(tj, aj), mean_period(t2, a2), 1e-2 * expected);
  // Nothing in the band, or too few samples: no mean period.
  EXPECT_TRUE(std::isnan(mean_period({0.0, 1.0}, {1.0, 1.0})));
  // A record read from a file carries it, and its length scale is its peak over (2 pi / T_m)^2.
  const auto record = read_record(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/records/mp-noise-20s.csv");
  EXPECT_EQ(record->t_m, mean_period(record->t, record->a));
  EXPECT_NEAR(record->length_scale(), record->peak * std::pow(record->t_m / (2.0 * std::numbers::pi), 2), 1e-15);
}

TEST(Loads, ACursorGivesThePulsesAnswersAndTheStepMeanIsTheInterpolationsIntegral) {
  std::vector<double> t, a;
  for (int i = 0; i < 500; ++i) {
    t.push_back(0.3 + 0.01 * i + 0.004 * std::sin(i));  // uneven, starting after 0
    a.push_back(std::cos(0.37 * i) + 0.2 * std::sin(1.3 * i));
  }
  const Pulse p = make_pulse(record_case(std::make_shared<const Record>(record_from_samples(t, a, "m")), 1.0, 1.0));
  LoadCursor cursor(p);
  const double h = 0.0137;
  for (int k = -5; k < 420; ++k) {
    const double t0 = k * h, t1 = (k + 1) * h;
    EXPECT_EQ(cursor.accel(t0), p.accel(t0)) << t0;
    EXPECT_EQ(cursor.sample(t1, h), p.sample(t1, h)) << t1;
    const double mean = cursor.mean(t0, t1);
    EXPECT_EQ(mean, p.mean(t0, t1)) << t0;
    // The integral piece by piece, split at every sample: the interpolation is linear on each
    // part, so the midpoint rule is exact there (and sees no jump at the record's ends).
    std::vector<double> cuts = {t0};
    for (double b : t)
      if (b > t0 && b < t1) cuts.push_back(b);
    cuts.push_back(t1);
    double sum = 0.0;
    for (std::size_t j = 0; j + 1 < cuts.size(); ++j)
      sum += (cuts[j + 1] - cuts[j]) * p.accel(0.5 * (cuts[j] + cuts[j + 1]));
    EXPECT_NEAR(mean, sum / h, 1e-13) << t0;
  }
  for (double x : {4.9, 0.31, 3.3, 3.2999, 5.5, 0.0, 2.0})  // backwards and by jumps
    EXPECT_EQ(cursor.accel(x), p.accel(x)) << x;
}

// Makris and Chang's Cn pulse: a_p cos(w t + phi_n) on (n + 1/2 - phi_n / pi) T_p leaves the
// ground at rest where it started: velocity and displacement zero at its end (to round-off).
TEST(Loads, AMakrisCnPulseEndsWithTheGroundBackAtRest) {
  for (int n : {1, 2, 3}) {
    Case c = test::make_case(Scene::pair, PulseShape::makris_c, 1.0, 0.5, 0.5);
    c.cycles = n;
    c.w_p = 3.0;
    c.a_p = 2.0;
    const Pulse p = make_pulse(c);
    const double phi = makris_phase(n), w = c.w_p, L = p.duration();
    EXPECT_NEAR(L, (n + 0.5 - phi / std::numbers::pi) * 2.0 * std::numbers::pi / w, 1e-15);
    const double v_end = p.mean(0.0, L) * L;  // the velocity the load leaves
    // displacement: integral of v(t) = (a / w)(sin(w t + phi) - sin phi)
    const double u_end = c.a_p / (w * w) * (std::cos(phi) - std::cos(w * L + phi)) - c.a_p / w * std::sin(phi) * L;
    EXPECT_LT(std::abs(v_end), 1e-14 * c.a_p / w) << n;
    EXPECT_LT(std::abs(u_end), 1e-14 * c.a_p / (w * w)) << n;
    RecordProperty("phi_" + std::to_string(n), sci(phi));
  }
}

// The mp acceleration (three sinusoids, cases/load.cpp) against the central difference of
// Mavroeidis and Papageorgiou's velocity (A/2)(1 + cos(w tau / gamma)) cos(w tau + nu): the
// difference's own error is (h^2 / 6) |v'''| ~ 1e-10 of a_p at h = 1e-5 / w.
TEST(Loads, TheMpAccelerationIsTheDerivativeOfItsVelocityPulse) {
  for (const auto& [gamma, nu] : {std::pair{2.0, 90.0}, {1.5, 0.0}, {3.0, -40.0}}) {
    Case c = test::make_case(Scene::pair, PulseShape::mp, 1.0, 0.5, 0.5);
    c.mp_gamma = gamma;
    c.mp_nu = nu;
    c.w_p = 2.0;
    c.a_p = 3.0;
    const Pulse p = make_pulse(c);
    const double w = c.w_p, A = c.a_p / w, half = gamma * std::numbers::pi / w;
    EXPECT_DOUBLE_EQ(p.duration(), 2.0 * half);
    const auto v = [&](double t) {
      const double tau = t - half;
      return 0.5 * A * (1.0 + std::cos(w * tau / gamma)) * std::cos(w * tau + nu * std::numbers::pi / 180.0);
    };
    double worst = 0.0;
    const double h = 1e-5 / w;
    for (int i = 1; i < 400; ++i) {
      const double t = p.duration() * i / 400.0;
      worst = std::max(worst, std::abs(p.accel(t) - (v(t + h) - v(t - h)) / (2.0 * h)));
    }
    EXPECT_LT(worst, 1e-8 * c.a_p) << gamma << " " << nu;
    EXPECT_NEAR(p.accel(0.0), 0.0, 1e-14 * c.a_p);  // continuous at both ends
    EXPECT_NEAR(p.accel(p.duration()), 0.0, 1e-13 * c.a_p);
    EXPECT_NEAR(p.mean(0.0, p.duration()) * p.duration(), v(p.duration()) - v(0.0), 1e-13 * A);
  }
}

// ---------------------------------------------------------------- the reference on them

Result reference(const Case& c) {
  const System s = make_system(c);
  return reference_solver().solve(s, Settings{});
}

// makris-a and makris-b are sine and cosine through the general load path (their sinusoid,
// the general oscillator): Pi1 within 1e-12 over the smoke set's scenes (measured: equal).
TEST(Loads, MakrisAAndBAreTheSineAndCosinePulsesThroughTheGeneralPath) {
  const CaseSet set = load_case_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/smoke.toml");
  double worst = 0.0;
  for (std::size_t i = 0; i < set.cases.size(); i += 2) {
    Case c = set.cases[i];
    const Result paper = reference(c);
    c.pulse = c.pulse == PulseShape::sine ? PulseShape::makris_a : PulseShape::makris_b;
    const Result general = reference(c);
    ASSERT_EQ(general.status, Status::ok) << c.family << ": " << general.message;
    worst = std::max(worst, std::abs(general.pi1 - paper.pi1) / paper.pi1);
    EXPECT_EQ(general.impacts, paper.impacts) << c.family << " pi2=" << c.pi2;
  }
  EXPECT_LT(worst, 1e-12);
  RecordProperty("worst_relative_difference", sci(worst));
}

// A record sampling a_p sin(w_p t) at T_p / n (and zero after) converges to the sine pulse's
// reference: linear interpolation is second order, and so is Pi1's error. Measured on a pair
// with impacts and a wall case: errors fall by ~4 per halving of the sampling interval.
TEST(Loads, ARecordSamplingTheSinePulseConvergesToItsReferenceAtSecondOrder) {
  for (Scene scene : {Scene::pair, Scene::wall}) {
    Case sine = test::make_case(scene, PulseShape::sine, 1.3, 0.5, 0.5);
    if (scene == Scene::wall) sine.pi2 = 0.6;
    const Result exact = reference(sine);
    ASSERT_EQ(exact.status, Status::ok);
    std::vector<double> errs;
    std::string measured;
    for (int n : {32, 64, 128, 256, 512}) {
      std::vector<double> t, a;
      const double t_p = 2.0 * std::numbers::pi;
      for (int i = 0; i <= n; ++i) {
        t.push_back(t_p * i / n);
        a.push_back(std::sin(t_p * i / n));
      }
      a.back() = 0.0;  // the sine pulse ends at zero
      Case c = record_case(std::make_shared<const Record>(record_from_samples(t, a, "sine")), 1.0, 1.0);
      c.scene = scene;
      c.pi2 = sine.pi2;
      const Result r = reference(c);
      ASSERT_EQ(r.status, Status::ok) << r.message;
      errs.push_back(std::abs(r.pi1 - exact.pi1) / exact.pi1);
      measured += " " + sci(errs.back());
    }
    const double order = test::observed_order(errs);
    EXPECT_GT(order, 1.8) << name(scene) << ":" << measured;
    EXPECT_LT(order, 2.3) << name(scene) << ":" << measured;
    EXPECT_LT(errs.back(), 1e-4) << name(scene) << ":" << measured;
    RecordProperty(std::string(name(scene)) + "_errors", measured);
    RecordProperty(std::string(name(scene)) + "_order", sci(order));
  }
}

// A ramp a_g = b t on [0, T], zero after, on one damped body with no contact (a wall far
// away): by hand, x'' + 2 xi w x' + w^2 x = -b t from rest gives
//   x = alpha + beta t + exp(-sigma t) (A cos(wd t) + B sin(wd t)),  beta = -b / w^2,
//   alpha = -2 xi beta / w,  A = -alpha,  B = (sigma A - beta) / wd,
// and after T the free motion from x(T), x'(T). The reference's history matches it to
// 1e-12 of the largest |x| (round-off of the closed forms).
TEST(Loads, ARampRecordFollowsTheMotionDerivedByHand) {
  const double b = 0.7, T = 3.0, w = 2.0, xi = 0.05;
  Case c = record_case(std::make_shared<const Record>(record_from_samples({0.0, T}, {0.0, b * T}, "ramp")), 1.0, 1.0);
  c.scene = Scene::wall;
  c.pi2 = w;
  c.pi3 = 1e6;  // the wall is never reached
  c.xi = xi;
  const System s = make_system(c);
  Settings st;
  st.history_samples = 400;
  const Result r = reference_solver().solve(s, st);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  const double sigma = xi * w, wd = w * std::sqrt(1.0 - xi * xi);
  const double beta = -b / (w * w), alpha = -2.0 * xi * beta / w, A = -alpha, B = (sigma * A - beta) / wd;
  const auto forced = [&](double t, double& x, double& v) {
    const double e = std::exp(-sigma * t), cs = std::cos(wd * t), sn = std::sin(wd * t);
    x = alpha + beta * t + e * (A * cs + B * sn);
    v = beta + e * ((-sigma * A + wd * B) * cs + (-sigma * B - wd * A) * sn);
  };
  double xT, vT;
  forced(T, xT, vT);
  const double a2 = xT, b2 = (vT + sigma * xT) / wd;
  double worst = 0.0, largest = 0.0;
  const int width = r.history.row_size();
  for (std::size_t k = 0; k < r.history.rows(); ++k) {
    const double t = r.history.data[k * static_cast<std::size_t>(width)];
    const double u = r.history.data[k * static_cast<std::size_t>(width) + 1];
    double x, v;
    if (t <= T) {
      forced(t, x, v);
    } else {
      const double tau = t - T;
      x = std::exp(-sigma * tau) * (a2 * std::cos(wd * tau) + b2 * std::sin(wd * tau));
    }
    worst = std::max(worst, std::abs(u - x));
    largest = std::max(largest, std::abs(x));
  }
  EXPECT_LT(worst, 1e-12 * largest) << sci(worst / largest);
  RecordProperty("relative_error", sci(worst / largest));
}

// A record's reference costs one event per sample, each a few microseconds: the shipped 40 s
// record at 0.005 s (8001 samples) on a pair with impacts takes milliseconds (measured 4.7 to
// 8.4 ms in RelWithDebInfo; bench/ times it). Here its work: one event per sample, plus the
// impacts. (A bound on its seconds failed CI under the sanitizers beside other tests: 0.52 s.)
TEST(Loads, TheReferenceOnAFortySecondRecordTakesOneEventPerSample) {
  Case c = record_case(read_record(kRecords + "mp-noise-40s.csv"), 0.0, 2.0 * std::numbers::pi);
  c.a_p = c.samples->peak;
  const Result r = reference(c);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_GE(r.steps, 8001);
  EXPECT_LT(r.steps, 8001 + 100);
}

// A case-set family over records: paths relative to the case file, a_p the record's peak,
// tp for w_p; both formats of one record give the same Pi1 to the AT2's digits.
TEST(Loads, ACaseSetTakesRecordsRelativeToItsFile) {
  const std::string text = R"(
name = "records"
[[family]]
name = "both"
scene = "pair"
pulse = "record"
record = ["../records/mp-noise-20s.csv", "../records/mp-noise-20s.at2"]
directivity = ["normal", "reverse"]
tp = 2
pi2 = [0.5, 2]
pi3 = 0.5
eps = 0.5
pi5 = 0.5
pi6 = 1
)";
  const CaseSet set = parse_case_set(text, std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/x.toml");
  ASSERT_EQ(set.cases.size(), 8u);
  const Case& c = set.cases[0];
  EXPECT_EQ(c.pulse, PulseShape::record);
  ASSERT_NE(c.samples, nullptr);
  EXPECT_EQ(c.a_p, c.samples->peak);
  EXPECT_DOUBLE_EQ(c.w_p, std::numbers::pi);
  EXPECT_NE(c.record.find("cases/records/mp-noise-20s.csv"), std::string::npos) << c.record;
  EXPECT_EQ(set.cases[4].samples->source.substr(set.cases[4].samples->source.size() - 4), ".at2");
  for (std::size_t i = 0; i < 4; ++i) {
    const double csv = reference(set.cases[i]).pi1, at2 = reference(set.cases[i + 4]).pi1;
    EXPECT_NEAR(at2, csv, 1e-6 * csv) << i;
  }
  // reverse flips the record: a different answer
  EXPECT_NE(reference(set.cases[0]).pi1, reference(set.cases[2]).pi1);
}

TEST(Loads, ACaseSetRefusesBadLoadKeysNamingTheLine) {
  const std::string dir = std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/x.toml";
  const auto error = [&](const std::string& family) {
    try {
      parse_case_set("name = \"x\"\n[[family]]\nname = \"f\"\nscene = \"wall\"\ndirectivity = \"normal\"\n"
                     "pi2 = 1\npi3 = 0.5\neps = 0.5\n" + family,
                     dir);
    } catch (const CaseSetError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  // A record without w_p or tp is no error: its w_p is its mean frequency (record_default_wp_test.cpp).
  EXPECT_EQ(error("pulse = \"record\"\nrecord = \"../records/mp-noise-20s.csv\"\n"), "(accepted)");
  const auto expect_refused = [&](const std::string& family, std::string_view says) {
    const std::string message = error(family);
    EXPECT_NE(message.find(says), std::string::npos) << message;
  };
  expect_refused("pulse = \"record\"\nrecord = \"nope.csv\"\ntp = 1\n", "x.toml:10: family[0].record: ");
  expect_refused("pulse = \"sine\"\ncycles = 2\n", "x.toml:10: family[0].cycles: not used by pulse sine");
  expect_refused("pulse = [\"sine\", \"mp\"]\nmp_gamma = 2\nmp_nu = 0\n", "used by pulse mp but not by sine");
  expect_refused("pulse = \"mp\"\nmp_gamma = 1\nmp_nu = 0\n", "x.toml:10: family[0].mp_gamma: must be in (1, 100] (got 1)");
  expect_refused("pulse = \"makris-c\"\n", "family[0].cycles: required by pulse makris-c");
  expect_refused("pulse = \"sine\"\ntp = 1\nw_p = 2\n", "family[0].tp: not with w_p (line 11)");
  expect_refused("pulse = \"sine\"\ntp = -1\n", "x.toml:10: family[0].tp: must be finite and > 0");
}

}  // namespace loads_tests
}  // namespace pb
