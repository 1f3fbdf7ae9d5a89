// The stress study's checks (studies/stress.hpp): pass and fail from hand-made rows at and
// around each tolerance, what a failed run counts against, and a tiny study end to end.

#include "studies/stress.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "cases/case_set.hpp"

namespace pb {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A finished pair run with delta = 0.5 a_p / w_p^2 (length scale 1) that broke no check.
Row good_row(double pi1 = 1.0) {
  Row r;
  r.input.family = "f";
  r.input.scene = Scene::pair;
  r.input.pi3 = 0.5;
  r.input.eps = 0.5;
  r.solver = "moreau-jean";
  r.settings = R"({"wh":2})";
  r.length_scale = 1.0;
  r.result.status = Status::ok;
  r.result.pi1 = pi1;
  r.result.min_gap = 0.0;
  r.wh = 2.0;
  r.penetration_steps = 0.0;
  r.result.energy_excess = 0.0;
  r.result.isolated_impacts = 2;
  r.result.restitution_low = 0.5;
  r.result.restitution_high = 0.5;
  r.cpu_seconds = 1.0;
  return r;
}

StressRow summary_of(const std::vector<Row>& rows, std::vector<double> reference = {}) {
  std::vector<const Row*> ptrs;
  for (const Row& r : rows) ptrs.push_back(&r);
  if (reference.empty()) reference.assign(rows.size(), kNaN);
  return summarize_stress(ptrs, reference);
}

TEST(StabilitySummary, CleanRunsPassEveryCheck) {
  const StressRow s = summary_of({good_row(), good_row()});
  EXPECT_EQ(s.family, "f");
  EXPECT_EQ(s.solver, "moreau-jean");
  EXPECT_EQ(s.settings, R"({"wh":2})");
  EXPECT_EQ(s.runs, 2u);
  EXPECT_EQ(s.ok, 2u);
  EXPECT_EQ(s.isolated_impacts, 4);
  EXPECT_EQ(s.finite, Verdict::pass);
  EXPECT_EQ(s.energy, Verdict::pass);
  EXPECT_EQ(s.gap, Verdict::pass);
  EXPECT_EQ(s.restitution, Verdict::pass);
  EXPECT_TRUE(s.passed());
}

TEST(StabilitySummary, EachCheckFailsJustAboveItsToleranceAndPassesAtIt) {
  // Energy: the worst excess of the family is judged.
  std::vector<Row> rows = {good_row(), good_row()};
  rows[1].result.energy_excess = kEnergyTolerance;
  EXPECT_EQ(summary_of(rows).energy, Verdict::pass);
  rows[1].result.energy_excess = 2 * kEnergyTolerance;
  StressRow s = summary_of(rows);
  EXPECT_EQ(s.energy, Verdict::fail);
  EXPECT_EQ(s.energy_excess_max, 2 * kEnergyTolerance);
  EXPECT_FALSE(s.passed());

  // Gap, time-stepper: judged in steps of travel, whatever the overlap over delta.
  rows = {good_row(), good_row()};
  rows[0].result.min_gap = -10.0;
  rows[0].penetration_steps = kPenetrationSteps;
  EXPECT_EQ(summary_of(rows).gap, Verdict::pass);
  rows[0].penetration_steps = 2 * kPenetrationSteps;
  s = summary_of(rows);
  EXPECT_EQ(s.gap, Verdict::fail);
  EXPECT_DOUBLE_EQ(s.penetration_steps_max, 2 * kPenetrationSteps);
  EXPECT_DOUBLE_EQ(s.penetration_max, 20.0);  // over delta = 0.5

  // Gap, the reference (no step): penetration is over delta (0.5 here).
  rows = {good_row(), good_row()};
  for (Row& r : rows) {
    r.solver = "event-driven";
    r.wh = r.penetration_steps = kNaN;
  }
  rows[0].result.min_gap = -0.5 * kReferencePenetration;
  s = summary_of(rows);
  EXPECT_EQ(s.gap, Verdict::pass);
  EXPECT_TRUE(std::isnan(s.penetration_steps_max));
  rows[0].result.min_gap = -0.5 * 2 * kReferencePenetration;
  EXPECT_EQ(summary_of(rows).gap, Verdict::fail);

  // Restitution: either end of the measured range may be the worst.
  rows = {good_row(), good_row()};
  rows[1].result.restitution_high = 0.5 + 0.5 * kRestitutionTolerance;
  EXPECT_EQ(summary_of(rows).restitution, Verdict::pass);
  rows[1].result.restitution_low = 0.5 - 2 * kRestitutionTolerance;
  s = summary_of(rows);
  EXPECT_EQ(s.restitution, Verdict::fail);
  EXPECT_NEAR(s.restitution_error_max, 2 * kRestitutionTolerance, 1e-15);
}

TEST(StabilitySummary, AFailedRunFailsFiniteOnlyAndItsStateIsNotJudged) {
  std::vector<Row> rows = {good_row(), good_row(), good_row()};
  rows[1].result.status = Status::diverged;
  rows[1].result.energy_excess = 1e30;  // what it blew up to: already counted by `finite`
  rows[1].result.min_gap = -1e30;
  rows[2].result.pi1 = std::numeric_limits<double>::infinity();  // status ok, Pi1 not finite
  const StressRow s = summary_of(rows);
  EXPECT_EQ(s.runs, 3u);
  EXPECT_EQ(s.ok, 1u);
  EXPECT_EQ(s.finite, Verdict::fail);
  EXPECT_EQ(s.energy, Verdict::pass);
  EXPECT_EQ(s.gap, Verdict::pass);
  EXPECT_EQ(s.isolated_impacts, 2);
  EXPECT_DOUBLE_EQ(s.cpu_median, 1.0);  // every run costs
}

TEST(StabilitySummary, UnmeasuredChecksAreNeitherPassNorFail) {
  std::vector<Row> rows = {good_row()};
  rows[0].result.energy_excess = kNaN;  // the solver keeps no energy balance
  rows[0].result.isolated_impacts = 0;
  rows[0].result.restitution_low = rows[0].result.restitution_high = kNaN;
  StressRow s = summary_of(rows);
  EXPECT_EQ(s.energy, Verdict::none);
  EXPECT_EQ(s.restitution, Verdict::none);
  EXPECT_EQ(s.gap, Verdict::pass);
  EXPECT_TRUE(s.passed());
  EXPECT_EQ(name(s.energy), "");

  rows[0].result.status = Status::time_limit;  // nothing finished: only `finite` judges
  s = summary_of(rows);
  EXPECT_EQ(s.finite, Verdict::fail);
  EXPECT_EQ(s.gap, Verdict::none);
  EXPECT_TRUE(std::isnan(s.penetration_max));
}

TEST(StabilitySummary, Pi1ErrorIsRelativeAndOnlyWhereBothRunsFinished) {
  std::vector<Row> rows = {good_row(1.1), good_row(2.4), good_row(3.0), good_row(9.0)};
  rows[3].result.status = Status::nan;
  const StressRow s = summary_of(rows, {1.0, 2.0, kNaN, 1.0});  // errors 0.1 and 0.2 only
  EXPECT_NEAR(s.pi1_err_median, 0.15, 1e-15);
  EXPECT_NEAR(s.pi1_err_max, 0.2, 1e-15);
  EXPECT_TRUE(std::isnan(pi1_error(rows[2], kNaN)));
  EXPECT_TRUE(std::isnan(pi1_error(rows[3], 1.0)));
  EXPECT_NEAR(pi1_error(rows[1], 2.0), 0.2, 1e-15);
}

TEST(StabilitySummary, CsvLineHasAFieldPerColumnAndSpellsTheVerdicts) {
  std::vector<Row> rows = {good_row()};
  rows[0].result.energy_excess = 1.0;
  const std::string line = stability_csv_line(summary_of(rows));
  const std::string header = stability_csv_header();
  EXPECT_EQ(std::count(line.begin(), line.end(), ','), std::count(header.begin(), header.end(), ','));
  EXPECT_EQ(line.substr(line.size() - std::string(",pass,fail,pass,pass").size()), ",pass,fail,pass,pass");
  EXPECT_EQ(header.substr(header.size() - std::string("finite,energy,gap,restitution").size()),
            "finite,energy,gap,restitution");
}

TEST(StressStudy, SummarisesTheTruthAndEverySettingPerFamily) {
  const CaseSet set = parse_case_set(R"(name = "tiny"
[defaults]
pulse = "sine"
directivity = "normal"
eps = 1
pi2 = [0.5, 2]
[[family]]
name = "pair"
scene = "pair"
pi3 = 0.5
pi5 = 0.5
pi6 = 1
[[family]]
name = "row3"
scene = "row3"
symmetric = true
pi3 = 0
pi5 = 2
pi6 = 1
)",
                                     "tiny.toml");
  const SettingsList list = parse_settings_list(R"(name = "t"
[[run]]
solver = "moreau-jean"
steps = 64
[[run]]
solver = "moreau-jean"
wh = [0.5, 100]
)",
                                                "t.toml");
  const Stress st = run_stress(set.cases, list, {});
  ASSERT_TRUE(st.complete);
  ASSERT_EQ(st.table.size(), 2u * 4u);  // 2 families x (the truth + 3 settings)
  EXPECT_EQ(st.runs.points.size(), 4u * 3u);
  for (std::size_t i = 0; i < st.table.size(); ++i) {
    const StressRow& row = st.table[i];
    EXPECT_EQ(row.family, i < 4 ? "pair" : "row3");
    EXPECT_EQ(row.runs, 2u);
    EXPECT_EQ(row.finite, Verdict::pass) << row.family << " " << row.settings;
    if (i % 4 == 0) {
      EXPECT_EQ(row.solver, "event-driven");  // the truth, not compared with itself
      EXPECT_TRUE(std::isnan(row.pi1_err_max));
    } else {
      EXPECT_EQ(row.solver, "moreau-jean");
      EXPECT_GE(row.pi1_err_max, 0.0) << row.settings;
    }
  }
  // Measured at N = 64: 3.7 % (pair, Pi2 = 0.5) and 0.18 % (row3) at most.
  EXPECT_LT(st.table[1].pi1_err_max, 0.05);
  EXPECT_LT(st.table[5].pi1_err_max, 0.005);
  for (std::size_t p = 0; p < set.cases.size(); ++p) EXPECT_TRUE(std::isfinite(st.truth[p])) << p;
}

}  // namespace
}  // namespace pb
