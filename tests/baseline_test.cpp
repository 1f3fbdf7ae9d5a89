// Accuracy regression baselines (studies/baseline.hpp, tests/baselines/): the stored rows are
// reproduced by the current solvers within each solver's stated tolerance, and the
// comparison catches what it must (a moved Pi1, a changed status, a lost or new case).
// A failure here means a solver's results changed: if on purpose, re-baseline with
// `poundbench baseline --update tests/baselines/FILE.csv` and say why in the commit.

#include "studies/baseline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cases/case_set.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "rows/row_read.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace baseline_tests {

namespace fs = std::filesystem;

const fs::path kBaselines = fs::path(POUNDBENCH_SOURCE_DIR) / "tests" / "baselines";

// Reruns what a stored baseline says made it and compares, as `baseline --check` does.
std::vector<Comparison> check(const std::string& name) {
  const fs::path file = kBaselines / name;
  const RowFile stored = read_csv_file(file.string());
  const BaselineHeader header = parse_header(stored.comments, file.string());
  const CaseSet set = load_case_set(kBaselines / header.cases);
  SettingsList list;
  if (!header.settings.empty()) list = load_settings_list(kBaselines / header.settings);
  const std::vector<Row> rows = run_baseline(set.cases, header.settings.empty() ? nullptr : &list, {});
  EXPECT_EQ(rows.size(), stored.rows.size()) << name;
  return compare_rows(rows, stored.rows, Match::same_setting);
}

void expect_reproduced(const std::string& name, std::size_t settings) {
  const std::vector<Comparison> table = check(name);
  ASSERT_FALSE(table.empty());
  std::size_t compared = 0;
  double worst = 0.0;
  std::vector<std::string> seen;
  for (const Comparison& c : table) {
    EXPECT_TRUE(c.passed(Match::same_setting))
        << name << ": " << c.family << " " << c.solver << " " << c.settings << ": " << c.failed << " failed, "
        << c.unmatched << " unmatched, " << c.missing << " missing, max " << c.max_difference << " at point "
        << c.worst_point;
    compared += c.compared;
    worst = std::max(worst, c.max_difference / c.tolerance);
    const std::string setting = c.solver + c.variant + c.settings;
    if (std::find(seen.begin(), seen.end(), setting) == seen.end()) seen.push_back(setting);
  }
  EXPECT_EQ(seen.size(), settings) << name;
  ::testing::Test::RecordProperty("compared", std::to_string(compared));
  ::testing::Test::RecordProperty("worst_over_tolerance", std::to_string(worst));
}

TEST(Baseline, ReferenceSpectraOfThePaperSetAreReproducedTo1e9) { expect_reproduced("paper-reference.csv", 1); }

TEST(Baseline, ReferenceOnTheStressSetIsReproducedTo1e9) { expect_reproduced("stress-reference.csv", 1); }

TEST(Baseline, ReferenceOnTheYieldingSetIsReproducedTo1e9) { expect_reproduced("yielding-reference.csv", 1); }

// The reference and the time-stepper settings of cases/settings/baseline.toml on the smoke set.
TEST(Baseline, EveryTimeStepperSettingOfTheListReproducesItsStoredRows) {
  std::size_t settings = 1 + 3;  // the reference, Moreau-Jean theta 1/2 and 1, its end-samples load
#ifdef POUNDBENCH_HAVE_ODE
  settings += 2;
#endif
#ifdef POUNDBENCH_HAVE_BULLET
  settings += 2;
#endif
  expect_reproduced("smoke.csv", settings);
}

// Siconos is optional: its settings are stored apart, and checked where it is built.
TEST(Baseline, SiconosSettingsReproduceTheirStoredRows) {
  if (!find_solver("siconos")) GTEST_SKIP() << "Siconos is not built here (libsiconos-kernel-dev not found)";
  expect_reproduced("smoke-siconos.csv", 1 + 3);  // the reference, Lemke, enumeration, LSODAR
}

TEST(Baseline, EveryStoredFileNamesItsCaseSetSettingsAndCommit) {
  for (const char* name :
       {"paper-reference.csv", "stress-reference.csv", "yielding-reference.csv", "smoke.csv", "smoke-siconos.csv"}) {
    const RowFile stored = read_csv_file((kBaselines / name).string());
    const BaselineHeader h = parse_header(stored.comments, name);
    EXPECT_TRUE(fs::exists(kBaselines / h.cases)) << name << ": " << h.cases;
    EXPECT_TRUE(h.settings.empty() || fs::exists(kBaselines / h.settings)) << name;
    bool commit = false;
    for (const std::string& note : h.notes) commit = commit || note.starts_with("commit: ");
    EXPECT_TRUE(commit) << name;
  }
}

// --- the comparison itself, on hand-made rows

Row row(double pi2, double pi1, const std::string& solver = "moreau-jean") {
  Row r;
  r.input.family = "f";
  r.input.pi2 = pi2;
  r.solver = solver;
  r.settings = solver == "event-driven" ? R"({"tol_scale":1})" : R"({"steps":64})";
  r.result.pi1 = pi1;
  return r;
}

TEST(BaselineCompare, APi1MovedBeyondTheToleranceFailsAndWithinItPasses) {
  const std::vector<Row> stored = {row(0.5, 2.0), row(1.0, 3.0)};
  std::vector<Row> rows = stored;
  rows[1].result.pi1 = 3.0 * (1.0 + 0.5e-12);
  std::vector<Comparison> t = compare_rows(rows, stored, Match::same_setting);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].tolerance, baseline_tolerance("moreau-jean"));
  EXPECT_TRUE(t[0].passed(Match::same_setting));
  EXPECT_EQ(t[0].compared, 2u);

  rows[1].result.pi1 = 3.0 * (1.0 + 2e-12);
  t = compare_rows(rows, stored, Match::same_setting);
  EXPECT_FALSE(t[0].passed(Match::same_setting));
  EXPECT_EQ(t[0].failed, 1u);
  EXPECT_NEAR(t[0].max_difference, 2e-12, 1e-15);
}

TEST(BaselineCompare, AChangedStatusFailsWhateverThePi1) {
  const std::vector<Row> stored = {row(0.5, 2.0)};
  std::vector<Row> rows = stored;
  rows[0].result.status = Status::step_cap;
  const std::vector<Comparison> t = compare_rows(rows, stored, Match::same_setting);
  EXPECT_EQ(t[0].failed, 1u);
  EXPECT_TRUE(std::isinf(t[0].max_difference));
}

TEST(BaselineCompare, LostAndNewCasesFailTheRegressionCheck) {
  const std::vector<Row> stored = {row(0.5, 2.0), row(1.0, 3.0)};
  const std::vector<Row> fewer = {stored[0]};
  std::vector<Comparison> t = compare_rows(fewer, stored, Match::same_setting);
  EXPECT_EQ(t[0].missing, 1u);
  EXPECT_FALSE(t[0].passed(Match::same_setting));

  std::vector<Row> moved = stored;
  moved[1].input.pi2 = 1.0 + 1e-3;  // another case: beyond kCaseMatchTolerance
  t = compare_rows(moved, stored, Match::same_setting);
  EXPECT_EQ(t[0].unmatched, 1u);
  EXPECT_EQ(t[0].missing, 1u);
  EXPECT_FALSE(t[0].passed(Match::same_setting));
}

// A case's numbers match within kCaseMatchTolerance (1e-5, relative), the nearer stored case
// where two are within it; names and whole numbers exactly.
TEST(BaselineCompare, CasesMatchWithinTheStatedToleranceOnTheirNumbersAndExactlyOnTheirNames) {
  const std::vector<Row> stored = {row(0.5, 2.0), row(0.500004, 3.0)};
  std::vector<Row> rows = {row(0.5000009, 2.0)};  // 1.8e-6 from the first, 6.2e-6 from the second
  std::vector<Comparison> t = compare_rows(rows, stored, Match::same_setting);
  EXPECT_EQ(t[0].compared, 1u);
  EXPECT_EQ(t[0].failed, 0u) << "matched to the nearer case, whose Pi1 it has";
  rows[0].input.pi2 = 0.5 * (1.0 - 2e-5);
  t = compare_rows(rows, stored, Match::same_setting);
  EXPECT_EQ(t[0].unmatched, 1u);
  ASSERT_EQ(t[0].unmatched_rows.size(), 1u);
  EXPECT_NE(t[0].unmatched_rows[0].nearest.find("point 0: pi2=0.5 (2.0e-05 apart)"), std::string::npos)
      << t[0].unmatched_rows[0].nearest;
  rows[0].input.pi2 = 0.5;
  rows[0].input.directivity = Directivity::reverse;
  t = compare_rows(rows, stored, Match::same_setting);
  ASSERT_EQ(t[0].unmatched_rows.size(), 1u);
  EXPECT_EQ(t[0].unmatched_rows[0].nearest, "no stored case of pair sine reverse with its setting");
}

TEST(BaselineCompare, ReferenceModeMatchesAnySolversRowsToTheStoredReferenceByPhysics) {
  const std::vector<Row> stored = {row(0.5, 2.0, "event-driven"), row(1.0, 3.0, "event-driven"),
                                   row(1.0, 3.3)};  // a stored time-stepper row: not the reference
  std::vector<Row> mine = {row(1.0, 3.03, "my-solver"), row(7.0, 1.0, "my-solver")};
  mine[0].input.family = "my label";  // labels and point indices do not matter
  mine[0].point = 99;
  const std::vector<Comparison> t = compare_rows(mine, stored, Match::reference, 0.02);
  ASSERT_EQ(t.size(), 2u);  // one line per family
  const Comparison& c = t[0].family == "my label" ? t[0] : t[1];
  EXPECT_EQ(c.compared, 1u);
  EXPECT_NEAR(c.max_difference, 0.01, 1e-12);
  EXPECT_EQ(c.worst_point, 99u);
  EXPECT_TRUE(c.passed(Match::reference));
  const Comparison& other = t[0].family == "my label" ? t[1] : t[0];
  EXPECT_EQ(other.unmatched, 1u);
  EXPECT_FALSE(other.passed(Match::reference));  // nothing to compare is not a pass
  EXPECT_FALSE(compare_rows(mine, stored, Match::reference, 0.005)[0].passed(Match::reference) &&
               compare_rows(mine, stored, Match::reference, 0.005)[1].passed(Match::reference));
}

TEST(BaselineCompare, ScenesMatchOnlyOnTheBodiesTheyHave) {
  // A wall case has no body 1: its Pi5 is not written, so it cannot tell two rows apart.
  Row stored = row(0.5, 2.0);
  stored.input.scene = Scene::wall;
  Row mine = stored;
  mine.input.pi5 = 0.25;
  EXPECT_EQ(compare_rows(std::vector{mine}, std::vector{stored}, Match::same_setting)[0].compared, 1u);
  stored.input.scene = mine.input.scene = Scene::pair;
  EXPECT_EQ(compare_rows(std::vector{mine}, std::vector{stored}, Match::same_setting)[0].unmatched, 1u);
}

TEST(BaselineHeader, LinesRoundTripAndAFileWithoutThemIsNotABaseline) {
  const BaselineHeader h{"../../cases/sets/smoke.toml", "", {"commit: abc", "made: today"}};
  const std::vector<std::string> lines = header_lines(h);
  const BaselineHeader back = parse_header(lines, "x.csv");
  EXPECT_EQ(back.cases, h.cases);
  EXPECT_EQ(back.settings, "");
  EXPECT_EQ(back.notes, h.notes);
  EXPECT_THROW(parse_header(std::vector<std::string>{" cases: a"}, "x.csv"), RowReadError);
  EXPECT_THROW(parse_header(std::vector<std::string>{lines[0], lines[2]}, "x.csv"), RowReadError);
}

// --- reading rows back

TEST(RowReader, RowsReadBackToTheCaseAndResultsTheyWereWrittenFrom) {
  Row r = row(1.0 / 3.0, 2.0 / 7.0);
  r.input.scene = Scene::chain;
  r.input.bodies = 12;
  r.input.kick = 1.5;
  r.input.a_p = 9.81;
  r.input.w_p = 6.283185307179586;
  r.length_scale = r.input.a_p / (r.input.w_p * r.input.w_p);
  r.point = 17;
  r.variant = "v";
  r.result.status = Status::diverged;
  r.result.message = "stopped, \"early\"\nsee log";
  r.result.impacts = 5;
  r.result.min_gap = -0.25 * r.length_scale;
  r.result.energy_excess = 1e-3;
  r.wh = 2.0;
  r.penetration_steps = 0.75;
  std::ostringstream out;
  out << "# a comment\n";
  write_csv(out, std::vector{r, row(2.0, 1.0)});
  std::istringstream in(out.str());
  const RowFile f = read_csv(in, "mem.csv");
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_EQ(f.comments, std::vector<std::string>{" a comment"});
  const Row& b = f.rows[0];
  EXPECT_EQ(csv_line(b), csv_line(r));  // every written column reads back to the same text
  EXPECT_EQ(b.input.bodies, 12);
  EXPECT_EQ(b.result.status, Status::diverged);
  EXPECT_EQ(b.result.message, r.result.message);
  EXPECT_EQ(b.input.pi2, 1.0 / 3.0);
}

TEST(RowReader, BadInputNamesFileLineColumnAndReason) {
  std::ostringstream out;
  write_csv(out, std::vector{row(1.0, 2.0)});
  std::string text = out.str();
  const std::string good = text;
  text.replace(text.find(",moreau-jean,"), 13, ",moreau-jean,,x,");  // two fields too many
  auto message = [](const std::string& csv) {
    std::istringstream in(csv);
    try {
      read_csv(in, "rows.csv");
    } catch (const RowReadError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::size_t columns = split_csv(csv_header()).size();
  EXPECT_EQ(message(text), "rows.csv:2: " + std::to_string(columns + 2) + " fields, the header has " +
                               std::to_string(columns));
  std::string bad_status = good;
  bad_status.replace(bad_status.find(",ok,"), 4, ",fine,");
  EXPECT_EQ(message(bad_status), "rows.csv:2: status: unknown name (\"fine\")");
  std::string bad_number = good;
  bad_number.replace(bad_number.find(",2,"), 3, ",2x,");
  EXPECT_EQ(message(bad_number), "rows.csv:2: pi1: not a number (\"2x\")");
  EXPECT_EQ(message("family,point\n"), "rows.csv:1: scene: missing column");
}

}  // namespace baseline_tests
}  // namespace pb
