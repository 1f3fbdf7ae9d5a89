// The step rule `record` (issue 34, Settings::steps_per_sample = k): on a record the step is
// DT / m, m the least whole number >= k whose step is no longer than T_min / N, so that the
// record's samples are steps' ends; it is refused on a pulse, which has no samples; `run`
// prints h / DT and the rows carry it; and a case in physical units takes the same step.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "cases/case_set.hpp"
#include "cases/record.hpp"
#include "cases/system.hpp"
#include "kit/fixed_step.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "tests/cli_fixture.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace record_step_tests {

const std::string kElCentro = kSource + "/cases/records/real/B-ELC000.AT2";

// The least m >= k with DT / m <= T_min / N, by counting up: not the rule's own arithmetic.
int least_m(double dt, double t_min, int n, int k) {
  int m = k;
  while (dt / m > t_min / n) ++m;
  return m;
}

TEST(RecordStep, TheRuleIsTheSamplingIntervalOverTheLeastWholeMForEveryCaseOfTheRealFamily) {
  const CaseSet set = load_case_set(kSource + "/cases/sets/workprecision-records.toml");
  ASSERT_FALSE(set.cases.empty());
  for (const Case& c : set.cases) {
    const System sys = make_system(c);
    ASSERT_TRUE(sys.pulse.record) << c.record;
    const double dt = sys.pulse.record->interval();
    for (int n : {8, 64, 1024})
      for (int k : {1, 2, 4}) {
        Settings s;
        s.steps = n;
        s.steps_per_sample = k;
        const int m = least_m(dt, sys.t_min, n, k);
        // Exact: both are DT / m in one division.
        EXPECT_EQ(time_step(sys, s, kDefaultSteps), dt / m) << c.record << " N " << n << " k " << k;
        EXPECT_LE(time_step(sys, s, kDefaultSteps), sys.t_min / n);
      }
    // Every sample time is a step's end: t_i = i DT = (i m) h to round-off (1e-12 relative).
    Settings s;
    s.steps_per_sample = 1;
    const double h = time_step(sys, s, kDefaultSteps);
    const double m = std::round(dt / h);
    const auto& t = sys.pulse.record->t;
    for (std::size_t i = 0; i < t.size(); i += 97)
      EXPECT_NEAR(static_cast<double>(i) * m * h, t[i], 1e-12 * (1.0 + t[i])) << c.record << " sample " << i;
  }
}

TEST(RecordStep, WithoutTheRuleTheStepIsTMinOverNOnARecordAsOnAPulse) {
  const CaseSet set = load_case_set(kSource + "/cases/sets/workprecision-records.toml");
  const System sys = make_system(set.cases.front());
  Settings s;
  EXPECT_EQ(time_step(sys, s, kDefaultSteps), sys.t_min / kDefaultSteps);
}

// Moreau-Jean's relative Pi1 error at N = 64, at T_min / N and under the rule (k = 1), on a
// point of the real-record family, against the reference 100x tighter (as the study measures).
std::pair<double, double> default_and_rule_errors(std::size_t point) {
  const CaseSet set = load_case_set(kSource + "/cases/sets/records-step.toml");
  const System sys = make_system(set.cases.at(point));
  Settings tight;
  tight.tol_scale = 0.01;
  const double exact = reference_solver().solve(sys, tight).pi1;
  Settings plain;
  plain.steps = 64;
  Settings rule = plain;
  rule.steps_per_sample = 1;
  const SolverInfo& mj = *find_solver("moreau-jean");
  return {std::abs(mj.solve(sys, plain).pi1 - exact) / exact, std::abs(mj.solve(sys, rule).pi1 - exact) / exact};
}

// The study's finding on real records either way (reports/records-step.csv, the rows of these
// points at N = 64): the rule meets 1 % where T_min / N does not on some points, and the
// opposite on others, because there the impacts, not the load's samples, set the error and a
// change of step moves the peak's cycle. CHY028-N (point 20): 2.1 % at T_min / N (h = 1.8 DT),
// 0.23 % under the rule (h = DT). AZF225 (point 11): 0.20 % at T_min / N (h = 0.30 DT), 3.3 %
// under the rule (h = DT / 4, a finer step).
// Both sides are a factor of 2 or more from 1 %.
TEST(RecordStep, OnOneRealRecordTheRuleMeetsOnePercentWhereTheDefaultNDoesNotAndOnAnotherTheOpposite) {
  const auto [chy_default, chy_rule] = default_and_rule_errors(20);
  EXPECT_GT(chy_default, 0.01);
  EXPECT_LT(chy_rule, 0.01);
  const auto [azf_default, azf_rule] = default_and_rule_errors(11);
  EXPECT_LT(azf_default, 0.01);
  EXPECT_GT(azf_rule, 0.01);
}

class RecordStepCli : public Cli {};

TEST_F(RecordStepCli, ThePulseRefusesTheRuleInOneLine) {
  const Outcome o = run("run --scene pair --pulse sine --directivity normal --pi2 1 --pi3 0.5 --eps 0.5 --pi5 0.5 "
                        "--pi6 1 --solver moreau-jean --steps-per-sample 1");
  EXPECT_EQ(o.exit_code, 2) << o.out;
  EXPECT_EQ(o.err.rfind("poundbench: --steps-per-sample: the step rule `record` needs a record's samples", 0), 0u)
      << o.err;
  EXPECT_EQ(line_count(o.err), 1u) << o.err;
  const Outcome negative = run("run --scene pair --pulse record --record '" + kElCentro +
                               "' --directivity normal --pi2 1 --pi3 0.5 --eps 0.5 --pi5 0.5 --pi6 1 --solver moreau-jean "
                               "--steps-per-sample -1");
  EXPECT_EQ(negative.exit_code, 2);
  EXPECT_NE(negative.err.find("--steps-per-sample: must be >= 1"), std::string::npos) << negative.err;
  EXPECT_EQ(line_count(negative.err), 1u) << negative.err;
}

TEST_F(RecordStepCli, RunPrintsHOverDtAndTheRowCarriesIt) {
  const std::string args = "run --scene pair --pulse record --record '" + kElCentro +
                           "' --directivity normal --pi2 1 --pi3 0.5 --eps 0.5 --pi5 0.5 --pi6 1 --solver moreau-jean";
  const Outcome text = run(args + " --steps-per-sample 2");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("steps_per_sample 2"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("step rule record"), std::string::npos) << text.out;
  const Outcome with = run(args + " --steps-per-sample 2 --json");
  const Outcome without = run(args + " --json");
  ASSERT_EQ(with.exit_code, 0) << with.err;
  ASSERT_EQ(without.exit_code, 0) << without.err;
  const auto w = nlohmann::json::parse(with.out), d = nlohmann::json::parse(without.out);
  // 1 / m with m a whole number >= 2; T_min / N is not tied to DT.
  const double m = 1.0 / w.at("h_over_dt").get<double>();
  EXPECT_NEAR(m, std::round(m), 1e-12 * m);
  EXPECT_GE(std::round(m), 2.0);
  EXPECT_LE(w.at("h_s").get<double>(), d.at("h_s").get<double>());
  EXPECT_DOUBLE_EQ(w.at("h_s").get<double>(), 0.005 / std::round(m));  // this file DT: 0.005 s
}

// The same buildings in seconds and metres and as Pi terms: the same step to the bit (T_min
// differs by the round-off of w0 = Pi2 w_p, far from moving the whole number m) and the same
// peak to the reference's agreement between the two (1e-9: physical_units_test).
TEST_F(RecordStepCli, APhysicalUnitsRunTakesTheSameStep) {
  const auto json = [&](const std::string& args) {
    const Outcome o = run("run --scene pair --pulse record --record '" + kElCentro + "' --eps 0.6" + args +
                          " --solver moreau-jean --steps-per-sample 1 --json");
    EXPECT_EQ(o.exit_code, 0) << o.err;
    return o.exit_code == 0 ? nlohmann::json::parse(o.out) : nlohmann::json::object();
  };
  const auto phys = json(" --t0 0.5 --t1 1 --gap 0.01");
  ASSERT_FALSE(phys.empty());
  char pi_terms[512];
  std::snprintf(pi_terms, sizeof pi_terms, " --directivity normal --pi2 %.17g --pi3 %.17g --pi5 %.17g --pi6 1",
                phys.at("pi2").get<double>(), phys.at("pi3").get<double>(), phys.at("pi5").get<double>());
  const auto pi = json(pi_terms);
  ASSERT_FALSE(pi.empty());
  EXPECT_EQ(pi.at("h_s"), phys.at("h_s"));
  EXPECT_EQ(pi.at("h_over_dt"), phys.at("h_over_dt"));
  EXPECT_NEAR(pi.at("pi1").get<double>(), phys.at("pi1").get<double>(), 1e-9 * phys.at("pi1").get<double>());
}

}  // namespace record_step_tests
}  // namespace pb
