// The gap that avoids pounding and the code rules (kit/separation.hpp), and scaled records
// (cases/record_scale.hpp): the reference's free motion against an independent integration,
// its symmetries, the rules' formula, and the scalings' targets met to round-off.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cases/case.hpp"
#include "cases/record.hpp"
#include "cases/record_scale.hpp"
#include "kit/separation.hpp"
#include "cases/system.hpp"
#include "rows/row.hpp"
#include "rows/row_read.hpp"
#include "solvers/registry.hpp"
#include "sweep/no_contact_cache.hpp"
#include "sweep/sweep.hpp"
#include "tests/cli_fixture.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace separation_tests {

const std::string kRecord = std::string(POUNDBENCH_SOURCE_DIR) + "/cases/records/real/B-ELC000.AT2";

Case pair_case(Directivity d = Directivity::normal) {
  Case c;
  c.scene = Scene::pair;
  c.pulse = PulseShape::sine;
  c.directivity = d;
  c.pi2 = 1.0;
  c.pi3 = 0.5;
  c.eps = 0.5;
  c.pi5 = 0.5;  // body 1 twice as stiff as body 0
  c.pi6 = 1.0;
  return c;
}

// The two free oscillators of a pair by classical RK4 on a fine grid (T_p / 60000, the pulse's
// end a step's end), independent of the reference's closed forms: body 0's peak, body 1's,
// and the largest u1 - u0 and u0 - u1 over the step ends.
struct Sampled {
  double peak0 = 0, peak1 = 0, closing = 0, opening = 0;
};
Sampled integrate(const System& s) {
  const double t_p = 2.0 * std::numbers::pi / s.pulse.w, h = t_p / 60000.0;
  const Body &b1 = s.bodies[0], &b0 = s.bodies[1];  // left to right: body 1, body 0
  // The load of the step's own piece: the cosine pulse jumps to zero at T_p, a step's end.
  bool after = false;
  const auto ag = [&](double t) { return after ? 0.0 : s.pulse.accel(std::min(t, t_p)); };
  const auto acc = [&](const Body& b, double t, double u, double v) { return -ag(t) - (b.c * v + b.k * u) / b.m; };
  double u[2] = {0, 0}, v[2] = {0, 0};
  Sampled out;
  const long n = std::lround(s.t_end / h);
  for (long k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * h;
    after = k >= 60000;
    for (int i = 0; i < 2; ++i) {
      const Body& b = i == 0 ? b1 : b0;
      const double k1u = v[i], k1v = acc(b, t, u[i], v[i]);
      const double k2u = v[i] + 0.5 * h * k1v, k2v = acc(b, t + 0.5 * h, u[i] + 0.5 * h * k1u, v[i] + 0.5 * h * k1v);
      const double k3u = v[i] + 0.5 * h * k2v, k3v = acc(b, t + 0.5 * h, u[i] + 0.5 * h * k2u, v[i] + 0.5 * h * k2v);
      const double k4u = v[i] + h * k3v, k4v = acc(b, t + h, u[i] + h * k3u, v[i] + h * k3v);
      u[i] += h / 6.0 * (k1u + 2 * k2u + 2 * k3u + k4u);
      v[i] += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
    out.peak1 = std::max(out.peak1, std::abs(u[0]));
    out.peak0 = std::max(out.peak0, std::abs(u[1]));
    out.closing = std::max(out.closing, u[0] - u[1]);
    out.opening = std::max(out.opening, u[1] - u[0]);
  }
  return out;
}

TEST(FreeMotion, MatchesAnIndependentIntegrationOfTheTwoOscillators) {
  for (const PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
    Case c = pair_case();
    c.pulse = p;
    const System s = make_system(c);
    const FreeMotion m = free_motion(s, Settings{});
    ASSERT_EQ(m.status, Status::ok) << m.message;
    const Sampled ref = integrate(s);
    // Sampled maxima fall short of the true ones by at most (h w)^2 / 8 of the amplitude.
    const double tol = 1e-7 * ref.peak0;
    EXPECT_NEAR(m.peak[1], ref.peak0, tol);
    EXPECT_NEAR(m.peak[0], ref.peak1, tol);
    EXPECT_NEAR(m.closing[0], ref.closing, tol);
    EXPECT_NEAR(m.opening[0], ref.opening, tol);
    EXPECT_GE(m.closing[0], ref.closing - 1e-15);  // exact: never below a sample
  }
}

TEST(FreeMotion, BodyZerosPeakIsTheNoContactPi1) {
  for (const Scene scene : {Scene::wall, Scene::pair, Scene::row3}) {
    Case c = pair_case();
    c.scene = scene;
    const System s = make_system(c);
    const FreeMotion m = free_motion(s, Settings{});
    ASSERT_EQ(m.status, Status::ok) << m.message;
    EXPECT_NEAR(s.pi1(m.peak[static_cast<std::size_t>(s.ref)]), no_contact_pi1(s, Settings{}), 1e-13);
  }
}

// For linear bodies the motion under -a_g is -u: what the bodies open under the load is
// what they close under it reversed.
TEST(FreeMotion, OpeningIsTheClosingUnderTheReversedLoad) {
  const FreeMotion given = free_motion(make_system(pair_case()), Settings{});
  const FreeMotion reversed = free_motion(make_system(pair_case(Directivity::reverse)), Settings{});
  EXPECT_NEAR(given.opening[0], reversed.closing[0], 1e-13 * given.opening[0]);
  EXPECT_NEAR(given.closing[0], reversed.opening[0], 1e-13 * given.closing[0]);
  EXPECT_NE(given.opening[0], given.closing[0]);  // the sine pulse is not symmetric
}

// A sweep keeps one free motion for both directivities of a linear system, the reversed one as
// its mirror: the same bits as its own solve.
TEST(FreeMotion, SweepCacheMirrorsTheReversedLoadToTheBit) {
  NoContactCache cache;
  for (const PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
    Case c = pair_case();
    c.pulse = p;
    const FreeMotion given = cache.free(make_system(c), Settings{});
    c.directivity = Directivity::reverse;
    const System reversed = make_system(c);
    const FreeMotion cached = cache.free(reversed, Settings{});
    const FreeMotion solved = free_motion(reversed, Settings{});
    EXPECT_EQ(cached.closing, solved.closing);
    EXPECT_EQ(cached.opening, solved.opening);
    EXPECT_EQ(cached.peak, solved.peak);
    EXPECT_EQ(cached.closing, given.opening);
  }
}

// Every body's peak with contact (run's peaks_m): body 1 of a pair is body 0 of the mirrored
// pair (left and right swapped, so the load's sign flips; Pi2 / Pi5, 1 / Pi5, 1 / Pi6 describe
// it), a different problem for the solver, whose Pi1 must be that peak.
TEST(BodyPeaks, TheLeftBodysPeakIsTheMirroredPairsPi1) {
  for (const char* solver : {"event-driven", "moreau-jean"}) {
    const SolverInfo& info = *find_solver(solver);
    Settings settings;
    if (!info.reference) settings.steps = 256;
    const Case c = pair_case();
    Row row = run_point(c, 0, info, settings);
    add_body_peaks(row, info, settings);
    ASSERT_EQ(row.peaks.size(), 2u) << solver;
    EXPECT_EQ(row.peaks[0], row.result.pi1);
    Case mirrored = c;
    mirrored.directivity = Directivity::reverse;
    mirrored.pi2 = c.pi2 / c.pi5;
    mirrored.pi5 = 1.0 / c.pi5;
    mirrored.pi6 = 1.0 / c.pi6;
    const Row other = run_point(mirrored, 0, info, settings);
    ASSERT_EQ(other.result.status, Status::ok) << other.result.message;
    // The reference to round-off; a time-stepper's step is T_min / N in both (the same T_min).
    EXPECT_NEAR(row.peaks[1], other.result.pi1, 1e-9 * other.result.pi1) << solver;
  }
}

TEST(SeparationRules, CqcCoefficientIsOneForEqualModesAndSymmetric) {
  EXPECT_DOUBLE_EQ(cqc_rho(0.05, 0.05, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(cqc_rho(0.0, 0.0, 1.0), 1.0);  // the limit
  EXPECT_NEAR(cqc_rho(0.05, 0.02, 0.7), cqc_rho(0.02, 0.05, 1.0 / 0.7), 1e-15);
  // Well separated modes hardly correlate; close ones do.
  EXPECT_LT(cqc_rho(0.05, 0.05, 0.5), 0.05);
  EXPECT_GT(cqc_rho(0.05, 0.05, 0.95), 0.5);
  const SeparationRules r = separation_rules(3.0, 4.0, 0.0);
  EXPECT_DOUBLE_EQ(r.abs, 7.0);
  EXPECT_DOUBLE_EQ(r.srss, 5.0);
  EXPECT_DOUBLE_EQ(r.ddc, 5.0);
  EXPECT_DOUBLE_EQ(separation_rules(3.0, 4.0, 1.0).ddc, 1.0);  // identical modes: |u_a - u_b|
}

// A row carries the separations; the required gap avoids every impact and a gap just under
// it does not (the reference's own solve, not the free motion).
TEST(SeparationRow, RequiredGapIsWhereImpactsStop) {
  const SolverInfo& ref = reference_solver();
  Row row = run_point(pair_case(), 0, ref, Settings{});
  ASSERT_EQ(row.result.status, Status::ok) << row.result.message;
  ASSERT_GT(row.separation, 0.0);
  EXPECT_EQ(row.peaks_no_contact.size(), 2u);
  EXPECT_NEAR(row.peaks_no_contact[0], row.pi1_no_contact, 1e-13);
  EXPECT_LE(row.separation, row.separation_abs * (1 + 1e-15));  // ABS bounds the relative motion
  for (const double f : {1.0 + 1e-9, 1.0 - 1e-6}) {
    Case c = pair_case();
    c.pi3 = row.separation * f;
    const Row r = run_point(c, 0, ref, Settings{});
    ASSERT_EQ(r.result.status, Status::ok) << r.result.message;
    EXPECT_EQ(r.result.impacts > 0, f < 1.0) << "gap " << f << " of the required one";
  }
  // And back from its CSV line, the list as written.
  const Row back = parse_row(split_csv(csv_line(row)));
  ASSERT_EQ(back.peaks_no_contact.size(), 2u);
  EXPECT_EQ(back.peaks_no_contact[1], row.peaks_no_contact[1]);
  EXPECT_EQ(back.separation_ddc, row.separation_ddc);
}

// A yielding body's motion is not its mirror under the reversed load: that one is solved again.
TEST(SeparationRow, YieldingReversedGapIsItsOwnSolve) {
  Case c = pair_case();
  c.pi_y0 = 0.2;
  const Row row = run_point(c, 0, reference_solver(), Settings{});
  ASSERT_EQ(row.result.status, Status::ok) << row.result.message;
  Case flipped = c;
  flipped.directivity = Directivity::reverse;
  const System fs = make_system(flipped);
  const FreeMotion m = free_motion(fs, Settings{});
  EXPECT_NEAR(row.separation_reversed, m.closing[0] / fs.length_scale(), 1e-13 * row.separation_reversed);
}

Case record_case() {
  Case c;
  c.scene = Scene::pair;
  c.pulse = PulseShape::record;
  c.record = kRecord;
  c.samples = read_record(kRecord);
  c.w_p = c.samples->mean_frequency();
  c.a_p = c.samples->peak;
  c.pi2 = 1.0;
  c.pi3 = 0.5;
  c.eps = 0.5;
  c.pi5 = 0.5;
  c.pi6 = 1.0;
  return c;
}

TEST(ScaledRecord, PgaTargetIsTheScaledPeak) {
  Case c = record_case();
  c.pga = 0.35 * kStandardGravity;
  ASSERT_FALSE(scale_record(c));
  EXPECT_NEAR(c.samples->peak, c.pga, 1e-15 * c.pga);
  EXPECT_NEAR(c.record_scale, c.pga / read_record(kRecord)->peak, 1e-15);
  EXPECT_FALSE(scale_record(c));  // applied once: nothing more
  EXPECT_EQ(c.samples->scale, c.record_scale);
}

TEST(ScaledRecord, SpectralTargetIsMetToRoundOff) {
  Case c = record_case();
  c.sa = 5.0;
  c.sa_period = 0.6;
  ASSERT_FALSE(scale_record(c));
  EXPECT_NEAR(pseudo_acceleration(*c.samples, 0.6, c.xi), 5.0, 1e-12);
  // The pseudo-acceleration is w^2 times the oscillator's peak: a case whose body 0 has that
  // period, solved without contact, has it.
  Case one = record_case();
  one.w_p = 2.0 * std::numbers::pi / 0.6;
  const System s = make_system(one);
  EXPECT_NEAR(pseudo_acceleration(*one.samples, 0.6, one.xi),
              one.w_p * one.w_p * no_contact_pi1(s, Settings{}) * s.length_scale(), 1e-12);
}

TEST(ScaledRecord, InPiTermsScalingIsOnlyAChangeOfUnit) {
  Case c = record_case();
  const double pi1 = run_point(c, 0, reference_solver(), Settings{}).result.pi1;
  c.record_scale = 2.5;
  ASSERT_FALSE(scale_record(c));
  c.a_p = c.samples->peak;
  EXPECT_NEAR(run_point(c, 0, reference_solver(), Settings{}).result.pi1, pi1, 1e-11 * pi1);
}

TEST(ScaledRecord, TwoWaysAtOnceAreRefused) {
  Case c = record_case();
  c.record_scale = 2.0;
  c.pga = 3.0;
  const auto bad = scale_record(c);
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->rfind("record_scale:", 0), 0u) << *bad;
}

class SeparationCli : public Cli {};

// The engineer's question as typed: two buildings in metres under a record scaled to 0.35 g.
TEST_F(SeparationCli, PhysicalRunScalesTheRecordAndReportsTheGaps) {
  const std::string base = "run --scene pair --pulse record --record " + kRecord +
                           " --t0 0.4 --t1 0.9 --m0 8e5 --m1 1.6e6 --gap 0.02 --eps 0.65";
  const Outcome o = run(base + " --pga-g 0.35 --json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_NEAR(j.at("pga").get<double>(), 0.35 * kStandardGravity, 1e-12);
  EXPECT_GT(j.at("record_scale").get<double>(), 0.0);
  EXPECT_NEAR(j.at("a_p").get<double>(), 0.35 * kStandardGravity, 1e-12);  // its peak, scaled
  for (const char* key : {"separation_m", "separation_reversed_m", "separation_abs_m", "separation_srss_m",
                          "separation_ddc_m", "residual_m"})
    EXPECT_TRUE(j.contains(key)) << key;
  ASSERT_EQ(j.at("peaks_no_contact_m").size(), 2u);
  EXPECT_NEAR(j.at("separation_abs_m").get<double>(),
              j.at("peaks_no_contact_m")[0].get<double>() + j.at("peaks_no_contact_m")[1].get<double>(), 1e-15);
  const Outcome refused = run(base + " --a-p 3.43");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find("--a-p:"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--pga"), std::string::npos) << refused.err;
  // A bad target is refused in one line naming its flag, before anything is computed from it
  // (NaN too: it is a target's "not given", and would scale nothing without a word).
  for (const auto& [flags, says] : {std::pair{" --pga nan", "--pga: must be finite and > 0"},
                                    {" --pga -1", "--pga: must be finite and > 0"},
                                    {" --sa 5", "--sa-period: required by sa"},
                                    {" --sa 5 --sa-period 1e-9", "--sa-period: must be finite and in"},
                                    {" --pga 3 --record-scale 2", "--record-scale: not with pga"}}) {
    const Outcome bad = run(base + flags);
    EXPECT_EQ(bad.exit_code, 2) << flags;
    EXPECT_EQ(bad.err.rfind(std::string("poundbench: ") + says, 0), 0u) << flags << ": " << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  }
}

}  // namespace separation_tests
}  // namespace pb
