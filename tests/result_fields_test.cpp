// The one table of a result's fields (rows/result_fields.hpp): every writer and reader of
// rows, --json, the Python dict and the external answer follows it, so a field given a
// value comes back through each of them (issue 47).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "frontend/run_output.hpp"
#include "programs/protocol.hpp"
#include "rows/result_fields.hpp"
#include "rows/row_read.hpp"
#include "kit/testing.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace result_fields_tests {
using test::make_case;

// A row of a pair case whose every number and count in Result differs from its default and
// from each other, so that a field read into the wrong place, or not read, shows.
Row distinct_row() {
  Row row;
  row.input = make_case(Scene::pair, PulseShape::sine, 1.0, 0.5, 0.5);
  row.solver = "moreau-jean";
  row.variant = "end-sample";
  row.settings = R"({"steps":64})";
  row.length_scale = 1.0;
  row.wh = 0.01;
  row.seconds = 0.02;
  row.cpu_seconds = 0.03;
  row.cpu_seconds_low = 0.025;
  row.cpu_seconds_high = 0.035;
  row.repetitions = 3;
  row.pi1_no_contact = 1.25;
  row.penetration_steps = 0.5;
  Result& r = row.result;
  r.message = "a, \"quoted\" note";
  r.resolved = false;
  r.unresolved = "energy";
  double x = 0.1;
  for (const ResultField& f : kResultFields) {
    if (f.real) r.*f.real = (x += 0.0625);
    if (f.whole) r.*f.whole = static_cast<long>(x += 1.0);
  }
  r.min_gap = -0.04;
  return row;
}

TEST(ResultFields, NameEveryColumnOfARowOnceAfterTheCasesColumns) {
  const std::vector<std::string> header = split_csv(csv_header());
  std::set<std::string> seen;
  for (const ResultField& f : kResultFields) {
    EXPECT_TRUE(seen.insert(std::string(f.name)).second) << f.name << " twice in the table";
    const auto count = std::count(header.begin(), header.end(), std::string(f.name));
    EXPECT_EQ(count, f.place == Place::none ? 0 : 1) << f.name;
  }
}

TEST(ResultFields, ComeBackFromARowsCsvLineFieldForField) {
  const Row row = distinct_row();
  const std::string line = csv_line(row);
  const Row back = parse_row(split_csv(line));
  EXPECT_EQ(csv_line(back), line);
  for (const ResultField& f : kResultFields) {
    if (f.place == Place::none) continue;
    if (f.type == ResultType::number || f.type == ResultType::count) {
      const double a = f.number(back), b = f.number(row);
      EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << f.name << ": " << a << " read back, " << b << " written";
    }
  }
}

TEST(ResultFields, AreRunJsonsKeysInTheTablesOrder) {
  const nlohmann::ordered_json j = app::row_json(distinct_row(), {});
  std::vector<std::string> results;
  for (const auto& [key, value] : j.items())
    if (find_result_field(key)) results.push_back(key);
  std::vector<std::string> expected;
  for (const ResultField& f : kResultFields)
    if (f.json) expected.emplace_back(f.name);
  EXPECT_EQ(results, expected);
  EXPECT_TRUE(j.at("settings").is_object());
  EXPECT_EQ(j.at("cpu_seconds").get<double>(), 0.03);
}

TEST(ResultFields, ThatAnAnswerCarriesComeBackFromAnAnswerDocument) {
  const System s = make_system(make_case(Scene::pair, PulseShape::sine, 1.0, 0.5, 0.5));
  Result r = distinct_row().result;
  r.status = Status::ok;
  r.message = "fine";
  r.step = s.t_end / 1000.0;  // within the run, as read_answer asks
  r.t_max = s.t_end / 2.0;
  Result back;
  ASSERT_EQ(programs::read_answer(programs::answer_document(r, s), s, Settings{}, back), "");
  for (const ResultField& f : kResultFields) {
    if (f.answer.empty() || !(f.real || f.whole)) continue;
    if (f.real == &Result::residual || f.real == &Result::hysteretic) continue;  // a yielding case's alone
    if (f.real) {
      EXPECT_EQ(back.*f.real, r.*f.real) << f.name;
    } else {
      EXPECT_EQ(back.*f.whole, r.*f.whole) << f.name;
    }
  }
  EXPECT_EQ(back.message, "fine");
}

}  // namespace result_fields_tests
}  // namespace pb
