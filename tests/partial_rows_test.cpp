// Rows read back from CSV (rows/row_read.hpp) and the partial files of resumed sweeps
// (output/partial_rows.hpp): a row read back prints the same line and the same derived
// values, and a partial file of another sweep is refused.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cases/case_set.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "output/partial_rows.hpp"
#include "rows/row_read.hpp"
#include "studies/stats.hpp"
#include "sweep/sweep.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace partial_rows_tests {

std::vector<Case> smoke_cases() {
  return load_case_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/smoke.toml").cases;
}

// The reference and a time-stepper with its monitor (energy, restitution, penetration).
std::vector<SweepRun> two_runs() {
  Settings coarse;
  coarse.steps = 16;
  return {{find_solver("event-driven"), Settings{}}, {find_solver("moreau-jean"), coarse}};
}

std::string text_of(std::span<const Row> rows, bool with_run) {
  std::string text = partial_header(with_run) + "\n";
  for (const Row& row : rows) text += partial_line(row, with_run) + "\n";
  return text;
}

std::vector<Row> read(const std::string& text, std::span<const Case> cases, std::span<const SweepRun> runs) {
  std::istringstream in(text);
  return read_partial_rows(in, "p.csv", cases, runs);
}

// The message of the PartialRowsError that reading `text` throws ("" if none).
std::string refusal(const std::string& text, std::span<const Case> cases, std::span<const SweepRun> runs) {
  try {
    read(text, cases, runs);
  } catch (const PartialRowsError& e) {
    return e.what();
  }
  return "";
}

TEST(RowRead, EveryRowOfASweepPrintsTheSameLineAndTheSameDerivedValues) {
  const std::vector<Case> cases = smoke_cases();
  SweepOptions options;
  options.threads = 2;
  std::vector<Row> rows = run_sweep(cases, two_runs(), options);
  Row chain = run_point([] {
    Case c;
    c.scene = Scene::chain;
    c.bodies = 4;
    c.kick = 0.5;
    c.eps = 1;
    return c;
  }(), 3, *find_solver("moreau-jean"), Settings{});
  rows.push_back(chain);
  Row failed = rows.front();
  failed.result.status = Status::failed;
  failed.result.message = "a \"quoted\", two-line\nmessage";
  rows.push_back(failed);

  std::size_t penetrating = 0;
  for (const Row& row : rows) {
    const std::string line = csv_line(row);
    const Row back = parse_row(split_csv(line));
    EXPECT_EQ(csv_line(back), line);
    // Exact: the summaries must not change by a bit when rows come back from a file.
    EXPECT_EQ(penetration(back), penetration(row)) << line;
    EXPECT_EQ(back.result.status, row.result.status);
    EXPECT_EQ(back.cpu_seconds, row.cpu_seconds);
    EXPECT_EQ(back.cpu_seconds_low, row.cpu_seconds_low);
    EXPECT_EQ(back.cpu_seconds_high, row.cpu_seconds_high);
    EXPECT_EQ(back.repetitions, row.repetitions);
    EXPECT_EQ(back.result.energy_excess, row.result.energy_excess) << line;
    if (penetration(row) > 0.0) ++penetrating;
  }
  EXPECT_GT(penetrating, 0u);  // the stepper's rows do overlap, so penetration was compared
}

// A file from before repetitions (no cpu_seconds_low, cpu_seconds_high, repetitions columns)
// reads back with the spread missing and one repetition, and its summary counts the one
// timing at both ends of the spread.
TEST(RowRead, AFileWithoutTheRepetitionColumnsReadsAsOneTiming) {
  Row row = run_point(smoke_cases()[2], 2, *find_solver("moreau-jean"), Settings{}, 3);
  ASSERT_GE(row.repetitions, 1);
  row.repetitions = 3;  // a row timed three times (a sanitizer build may spend the budget sooner)
  std::vector<std::string> header = split_csv(csv_header()), fields = split_csv(csv_line(row));
  // Without the three repetition columns (and the load columns appended after them).
  const auto at = static_cast<std::size_t>(std::find(header.begin(), header.end(), "cpu_seconds_low") - header.begin());
  header.resize(at);
  fields.resize(at);
  const Row back = parse_row(Columns(header), fields);
  EXPECT_EQ(back.cpu_seconds, row.cpu_seconds);
  EXPECT_TRUE(std::isnan(back.cpu_seconds_low));
  EXPECT_TRUE(std::isnan(back.cpu_seconds_high));
  EXPECT_EQ(back.repetitions, 1);
  const Row* one[] = {&back};
  const CpuCost cost = cpu_cost(one);
  EXPECT_EQ(cost.median_low, row.cpu_seconds);
  EXPECT_EQ(cost.median_high, row.cpu_seconds);
  EXPECT_EQ(cost.repetitions, 1);
}

// RFC 4180 as the rows are written: a separator inside quotes is text, a doubled quote there is
// one quote, and empty fields count (at the end too).
TEST(RowRead, SplitCsvKeepsQuotedSeparatorsAndDoubledQuotes) {
  EXPECT_EQ(split_csv(R"(a,"b,""c""",,d,)"), (std::vector<std::string>{"a", R"(b,"c")", "", "d", ""}));
  EXPECT_EQ(split_csv(R"("{""steps"":64}")"), (std::vector<std::string>{R"({"steps":64})"}));
  EXPECT_EQ(split_csv(""), (std::vector<std::string>{""}));
  EXPECT_EQ(split_csv(R"(x,"",y)"), (std::vector<std::string>{"x", "", "y"}));
  const std::string record = R"(a,"b,""c""",,d)";
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(csv_field(record, k), split_csv(record)[k]) << k;
  EXPECT_EQ(csv_field(record, 4), "");
}

TEST(RowRead, ABadFieldIsRefusedNamingItsColumn) {
  std::vector<std::string> fields = split_csv(csv_line(Row{}));
  fields[20] = "1.5x";  // pi1
  try {
    parse_row(fields);
    FAIL() << "read a bad pi1";
  } catch (const RowReadError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("pi1: not a number", 0), 0u) << e.what();
  }
  fields.pop_back();
  EXPECT_THROW(parse_row(fields), RowReadError);
}

TEST(RowRead, RecordsSpanQuotedLineBreaksAndALastLineCutShortIsNoRecord) {
  std::istringstream in("a,\"two\nlines\",c\nd,e\nf,\"cut");
  std::string record;
  ASSERT_TRUE(read_csv_record(in, record));
  EXPECT_EQ(record, "a,\"two\nlines\",c");
  ASSERT_TRUE(read_csv_record(in, record));
  EXPECT_EQ(record, "d,e");
  EXPECT_FALSE(read_csv_record(in, record));
}

TEST(PartialRows, ReadsBackEveryRowSortedByTaskDroppingATornLastLine) {
  const std::vector<Case> cases = smoke_cases();
  const std::vector<SweepRun> runs = two_runs();
  SweepOptions options;
  options.threads = 2;
  const std::vector<Row> rows = run_sweep(cases, runs, options);
  std::vector<Row> shuffled = rows;
  std::reverse(shuffled.begin(), shuffled.end());  // as rows finish: in any order

  const std::string text = text_of(shuffled, true);
  const std::vector<Row> back = read(text + "0,wall-sine,3,wa", cases, runs);
  ASSERT_EQ(back.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(back[i].run, rows[i].run);
    EXPECT_EQ(csv_line(back[i]), csv_line(rows[i]));
  }
  EXPECT_TRUE(read("", cases, runs).empty());

  // A sweep of one run has no run column; the rows read are the points written, by point.
  const std::vector<SweepRun> one(runs.begin(), runs.begin() + 1);
  const std::vector<Row> some = {rows[0], rows[7], rows[3]};
  const std::vector<Row> read_one = read(text_of(some, false), cases, one);
  std::vector<std::size_t> points;
  for (const Row& r : read_one) points.push_back(r.point);
  EXPECT_EQ(points, (std::vector<std::size_t>{0, 3, 7}));
}

TEST(PartialRows, AFileOfAnotherSweepIsRefusedNamingTheLineAndTheField) {
  const std::vector<Case> cases = smoke_cases();
  const std::vector<SweepRun> runs = two_runs();
  const std::vector<Row> rows = {run_point(cases[2], 2, *runs[0].solver, runs[0].settings),
                                 run_point(cases[4], 4, *runs[0].solver, runs[0].settings)};
  const std::vector<SweepRun> reference(runs.begin(), runs.begin() + 1);
  ASSERT_EQ(read(text_of(rows, false), cases, reference).size(), 2u);

  // Other settings: the reference at another tolerance.
  std::vector<SweepRun> looser = reference;
  looser[0].settings.tol_scale = 10;
  EXPECT_EQ(refusal(text_of(rows, false), cases, looser).rfind("p.csv:2: point 2: settings is", 0), 0u)
      << refusal(text_of(rows, false), cases, looser);
  // Another solver.
  const std::vector<SweepRun> stepper(runs.begin() + 1, runs.end());
  EXPECT_NE(refusal(text_of(rows, false), cases, stepper).find("solver is \"event-driven\" there"), std::string::npos);
  // Another case set: point 4 is another case, or there is no point 4.
  std::vector<Case> other = cases;
  other[4].pi2 *= 2;
  EXPECT_EQ(refusal(text_of(rows, false), other, reference).rfind("p.csv:3: point 4: pi2 is", 0), 0u);
  EXPECT_NE(refusal(text_of(rows, false), std::span(cases).first(4), reference).find("this sweep has 4 points"),
            std::string::npos);
  // A study's file (run column) given to a spectrum, a bad row, another header.
  EXPECT_NE(refusal(text_of(rows, true), cases, reference).find("header"), std::string::npos);
  EXPECT_NE(refusal(text_of(rows, false) + "x,y\n", cases, reference).find("p.csv:4: not a row"), std::string::npos);
}

// A row's line with the field of `column` replaced by `value`.
std::string edited(const std::string& line_of_row, const std::string& column, const std::string& value) {
  const std::vector<std::string> header = split_csv(csv_header());
  std::vector<std::string> fields = split_csv(line_of_row);
  fields.at(static_cast<std::size_t>(std::find(header.begin(), header.end(), column) - header.begin())) = value;
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + csv_field(fields[i]);
  return line;
}

// A row read back passes the check of a row written (row_problem), and a point has one
// row: anything else is refused with the file and the line, never taken or dropped.
TEST(PartialRows, ADamagedRowOrASecondRowOfOnePointIsRefusedNamingTheLine) {
  const std::vector<Case> cases = smoke_cases();
  const std::vector<SweepRun> runs = two_runs();
  const std::vector<SweepRun> reference(runs.begin(), runs.begin() + 1);
  const Row good = run_point(cases[2], 2, *runs[0].solver, runs[0].settings);
  const Row other = run_point(cases[4], 4, *runs[0].solver, runs[0].settings);
  ASSERT_EQ(good.result.status, Status::ok);
  ASSERT_EQ(row_problem(good), "");
  const std::string head = partial_header(false) + "\n" + csv_line(other) + "\n";

  const std::vector<std::pair<std::string, std::string>> damaged = {
      {"pi1", "nan"}, {"pi1", ""}, {"pi1", "inf"}, {"pi1", "-1"}, {"impacts", "-5"}, {"steps", "-1"},
      {"cpu_seconds", "-inf"}, {"cpu_seconds_high", "-1"}, {"repetitions", "0"}};
  for (const auto& [column, value] : damaged) {
    const std::string why = refusal(head + edited(csv_line(good), column, value) + "\n", cases, reference);
    EXPECT_EQ(why.rfind("p.csv:3: not a row: " + column + ": must be", 0), 0u) << column << "=" << value << ": " << why;
    EXPECT_NE(why.find("delete the line"), std::string::npos) << why;
  }
  // A failed or diverged row has no Pi1 to check.
  EXPECT_EQ(read(head + edited(edited(csv_line(good), "status", "failed"), "pi1", "") + "\n", cases, reference).size(), 2u);

  // Two rows of point 4, even identical ones.
  EXPECT_EQ(refusal(head + csv_line(good) + "\n" + csv_line(other) + "\n", cases, reference),
            "p.csv:4: point 4: a second row (the first is on line 2); delete one of the two lines");
  const std::string study = text_of(std::vector<Row>{good, good}, true);
  EXPECT_EQ(refusal(study, cases, runs), "p.csv:3: point 2 of run 0: a second row (the first is on line 2); "
                                         "delete one of the two lines");
}

// What a solver returns that the row check refuses becomes a failed row, so that the
// sweep never writes a row it would refuse on resume.
TEST(RowCheck, RowsWrittenPassTheChecksOfRowsRead) {
  Row row;
  row.result.status = Status::ok;
  row.result.pi1 = 1.5;
  EXPECT_EQ(row_problem(row), "");
  row.result.impacts = -5;
  EXPECT_EQ(row_problem(row), "impacts: must be >= 0 (it is -5)");
  row.result.impacts = 0;
  row.result.pi1 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(row_problem(row), "pi1: must be a finite number >= 0 when status is ok (it is nan)");
  row.result.status = Status::nan;
  EXPECT_EQ(row_problem(row), "");
  row.seconds = std::numeric_limits<double>::quiet_NaN();  // a baseline's empty timing
  EXPECT_EQ(row_problem(row), "");
}

}  // namespace partial_rows_tests
}  // namespace pb
