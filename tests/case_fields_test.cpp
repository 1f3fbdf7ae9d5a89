// The table of a Case's numbers (cases/fields.hpp) is what the flags, the CSV columns, the
// row key and the JSON are made from: every field must survive each of them, and appear
// only for the scenes that use it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "cases/fields.hpp"
#include "rows/row.hpp"
#include "rows/row_read.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace case_fields_tests {

// A case of `scene` and `pulse` with every field set to a value of its own (none of them a default).
Case distinctive(Scene scene, PulseShape pulse = PulseShape::sine) {
  Case c;
  c.scene = scene;
  c.pulse = pulse;
  c.bodies = scene == Scene::chain ? 7 : 0;
  c.cycles = pulse == PulseShape::makris_c ? 3 : 0;
  if (pulse == PulseShape::record) c.record = "records/a, \"b\".csv";  // quoted in CSV
  double x = 0.125;
  for (const CaseField& f : kCaseFields) {
    if (!used_by(f, scene, pulse) || !f.number) continue;
    c.*f.number = x;
    x += 0.0625;
  }
  return c;
}

TEST(CaseFields, EveryFieldRoundTripsThroughACsvRowInEveryScene) {
  const std::vector<std::pair<Scene, PulseShape>> cases = {
      {Scene::wall, PulseShape::sine},     {Scene::pair, PulseShape::cosine}, {Scene::row3, PulseShape::sine},
      {Scene::chain, PulseShape::sine},    {Scene::pair, PulseShape::makris_c}, {Scene::row3, PulseShape::mp},
      {Scene::wall, PulseShape::record}};
  for (const auto& [scene, pulse] : cases) {
    Row row;
    row.input = distinctive(scene, pulse);
    row.solver = "event-driven";
    row.result.pi1 = 1.0;
    const Row back = parse_row(split_csv(csv_line(row)));
    for (const CaseField& f : kCaseFields) {
      // A field the case does not use is written empty and read back as the Case default.
      const bool used = used_by(f, scene, pulse);
      if (f.text) {
        EXPECT_EQ(back.input.*f.text, used ? row.input.*f.text : std::string()) << f.name;
        continue;
      }
      const double expected = used ? f.get(row.input) : f.get(Case{});
      // NaN: a record's scaling target not given, read back as not given.
      if (std::isnan(expected))
        EXPECT_TRUE(std::isnan(f.get(back.input))) << f.name << " in " << name(scene) << " " << name(pulse);
      else
        EXPECT_EQ(f.get(back.input), expected) << f.name << " in " << name(scene) << " " << name(pulse);
    }
    EXPECT_EQ(case_key(back.input), case_key(row.input)) << name(scene) << " " << name(pulse);
  }
}

TEST(CaseFields, EveryFieldIsAColumnAndAFlagOfItsOwnName) {
  const std::vector<std::string> header = split_csv(csv_header());
  for (const CaseField& f : kCaseFields) {
    EXPECT_EQ(std::count(header.begin(), header.end(), std::string(f.name)), 1) << f.name;
    EXPECT_EQ(flag_of(f).substr(0, 2), "--");
    EXPECT_EQ(flag_of(f).find('_'), std::string::npos) << flag_of(f);
  }
  EXPECT_EQ(flag_of(kCaseFields[8]), "--n-free");
}

TEST(CaseFields, TheRowKeyTellsApartCasesThatDifferInAnyUsedField) {
  const Case base = distinctive(Scene::chain);
  for (const CaseField& f : kCaseFields) {
    if (!used_by(f, Scene::chain, PulseShape::sine)) continue;
    Case other = base;
    if (f.integer)
      other.*f.integer += 1;
    else
      other.*f.number *= 1.5;
    EXPECT_NE(case_key(other), case_key(base)) << f.name;
  }
}

}  // namespace case_fields_tests
}  // namespace pb
