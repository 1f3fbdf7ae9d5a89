// The stress study's checks (studies/stress.hpp): pass and fail from hand-made rows at and
// around each tolerance, what a failed run counts against, and a tiny study end to end.

#include "studies/stress.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "cases/case_set.hpp"
#include "rows/row_read.hpp"
#include "kit/testing.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace stability_tests {

using test::kNaN;

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

StressRow summary_of(const std::vector<Row>& rows, std::vector<TruthPoint> truth = {}) {
  std::vector<const Row*> ptrs;
  for (const Row& r : rows) ptrs.push_back(&r);
  if (truth.empty()) truth.assign(rows.size(), TruthPoint{});
  return summarize_stress(ptrs, truth);
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

  // Gap, time-stepper: judged in steps of travel, whatever the overlap over a_p / w_p^2.
  rows = {good_row(), good_row()};
  rows[0].result.min_gap = -10.0;
  rows[0].penetration_steps = kPenetrationSteps;
  EXPECT_EQ(summary_of(rows).gap, Verdict::pass);
  rows[0].penetration_steps = 2 * kPenetrationSteps;
  s = summary_of(rows);
  EXPECT_EQ(s.gap, Verdict::fail);
  EXPECT_DOUBLE_EQ(s.penetration_steps_max, 2 * kPenetrationSteps);
  EXPECT_DOUBLE_EQ(s.penetration_max, 10.0);  // over a_p / w_p^2 = 1, not delta = 0.5

  // Gap, the reference (no step): penetration over a_p / w_p^2 (1 here), whatever delta.
  rows = {good_row(), good_row()};
  for (Row& r : rows) {
    r.solver = "event-driven";
    r.wh = r.penetration_steps = kNaN;
  }
  rows[0].result.min_gap = -kReferencePenetration;
  s = summary_of(rows);
  EXPECT_EQ(s.gap, Verdict::pass);
  EXPECT_TRUE(std::isnan(s.penetration_steps_max));
  rows[0].result.min_gap = -2 * kReferencePenetration;
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
  EXPECT_DOUBLE_EQ(s.cpu.median, 1.0);  // every run costs
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
  const StressRow s = summary_of(rows, {{1.0}, {2.0}, {kNaN}, {1.0}});  // errors 0.1 and 0.2 only
  EXPECT_NEAR(s.pi1_err_median, 0.15, 1e-15);
  EXPECT_NEAR(s.pi1_err_max, 0.2, 1e-15);
  EXPECT_TRUE(std::isnan(pi1_error(rows[2], kNaN)));
  EXPECT_TRUE(std::isnan(pi1_error(rows[3], 1.0)));
  EXPECT_NEAR(pi1_error(rows[1], 2.0), 0.2, 1e-15);
}

// Accuracy judges the runs compared with the truth: the 95th percentile of their Pi1 error
// against kAccuracyTolerance, and any point where the truth has an impact and the run none.
TEST(StabilitySummary, AccuracyFailsAboveItsToleranceOrOnAMissedImpact) {
  // 20 runs: the 95th percentile interpolates between the 19th and 20th smallest errors.
  std::vector<Row> rows(20, good_row(1.0));
  std::vector<TruthPoint> truth(20, TruthPoint{1.0, 3});
  for (Row& r : rows) r.result.impacts = 3;
  rows[19].result.pi1 = 1.0 + kAccuracyTolerance;  // the largest error alone is at the tolerance
  StressRow s = summary_of(rows, truth);
  EXPECT_NEAR(s.pi1_err_p95, 0.05 * kAccuracyTolerance, 1e-15);
  EXPECT_EQ(s.accuracy, Verdict::pass);
  EXPECT_EQ(s.impacts, 60);
  EXPECT_EQ(s.truth_impacts, 60);
  EXPECT_EQ(s.missed_impact_points, 0u);

  rows[18].result.pi1 = rows[19].result.pi1 = 1.0 + 1.1 * kAccuracyTolerance;  // two far off: p95 above
  s = summary_of(rows, truth);
  EXPECT_GT(s.pi1_err_p95, kAccuracyTolerance);
  EXPECT_EQ(s.accuracy, Verdict::fail);
  EXPECT_EQ(s.failed_checks(), "accuracy");

  // Pi1 right, but one point's impacts all missed; a point where the truth has none is not.
  rows.assign(20, good_row(1.0));
  truth[3].impacts = 0;
  for (Row& r : rows) r.result.impacts = 3;
  rows[3].result.impacts = 0;
  EXPECT_EQ(summary_of(rows, truth).accuracy, Verdict::pass);
  rows[4].result.impacts = 0;
  s = summary_of(rows, truth);
  EXPECT_EQ(s.missed_impact_points, 1u);
  EXPECT_EQ(s.accuracy, Verdict::fail);
  EXPECT_EQ(s.impacts, 54);
  EXPECT_EQ(s.truth_impacts, 57);

  // Only compared runs count: not a failed run, nor one whose truth did not finish.
  rows[4].result.status = Status::diverged;
  truth[5].pi1 = kNaN;
  rows[5].result.impacts = 0;
  s = summary_of(rows, truth);
  EXPECT_EQ(s.missed_impact_points, 0u);
  EXPECT_EQ(s.truth_impacts, 51);
  EXPECT_EQ(s.accuracy, Verdict::pass);
  EXPECT_EQ(s.failed_checks(), "finite");
  // Nothing compared (the truth's own rows): none.
  EXPECT_EQ(summary_of(rows).accuracy, Verdict::none);
}

TEST(StabilitySummary, CsvLineHasAFieldPerColumnAndSpellsTheVerdicts) {
  std::vector<Row> rows = {good_row()};
  rows[0].result.energy_excess = 1.0;
  const std::string line = stability_csv_line(summary_of(rows));
  const std::string header = stability_csv_header();
  EXPECT_EQ(std::count(line.begin(), line.end(), ','), std::count(header.begin(), header.end(), ','));
  const std::vector<std::string> columns = split_csv(header), fields = split_csv(line);
  const auto field = [&](std::string_view column) {
    return fields.at(static_cast<std::size_t>(std::find(columns.begin(), columns.end(), column) - columns.begin()));
  };
  EXPECT_EQ(field("finite"), "pass");
  EXPECT_EQ(field("energy"), "fail");
  EXPECT_EQ(field("gap"), "pass");
  EXPECT_EQ(field("restitution"), "pass");
  EXPECT_EQ(field("accuracy"), "");  // not compared with a truth
  // Appended columns keep the earlier ones where they were, the verdicts first and last.
  EXPECT_EQ(columns[17], "restitution");
  EXPECT_EQ(columns.back(), "accuracy");
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
wh = [0.5, 6]
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
  // Stable but wrong shows: at w_max h = 6 (just within the step bound: the pulse sets w_max
  // here) the stepper passes every stability check and fails accuracy; at 0.5 it passes it.
  for (std::size_t family : {0u, 4u}) {
    const StressRow &fine = st.table[family + 2], &coarse = st.table[family + 3];
    ASSERT_EQ(fine.settings.substr(0, 10), R"({"wh":0.5,)");
    ASSERT_EQ(coarse.settings.substr(0, 8), R"({"wh":6,)");
    EXPECT_EQ(fine.accuracy, Verdict::pass) << fine.family << ": " << fine.pi1_err_p95;
    EXPECT_EQ(coarse.accuracy, Verdict::fail) << coarse.family << ": " << coarse.pi1_err_p95;
    EXPECT_EQ(coarse.failed_checks(), "accuracy") << coarse.family;
    EXPECT_EQ(st.table[family].accuracy, Verdict::none);  // the truth
  }
  for (std::size_t p = 0; p < set.cases.size(); ++p) EXPECT_TRUE(std::isfinite(st.truth[p].pi1)) << p;
}

}  // namespace stability_tests
}  // namespace pb
