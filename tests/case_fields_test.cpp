// The table of a Case's numbers (cases/fields.hpp) is what the flags, the CSV columns, the
// row key and the JSON are made from: every field must survive each of them, and appear
// only for the scenes that use it.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cases/fields.hpp"
#include "rows/row.hpp"
#include "rows/row_read.hpp"

namespace pb {
namespace {

// A case of `scene` with every number set to a value of its own (none of them a default).
Case distinctive(Scene scene) {
  Case c;
  c.scene = scene;
  c.bodies = scene == Scene::chain ? 7 : 0;
  double x = 0.125;
  for (const CaseField& f : kCaseFields) {
    if (!used_by(f, scene) || f.integer) continue;
    c.*f.number = x;
    x += 0.0625;
  }
  return c;
}

TEST(CaseFields, EveryFieldRoundTripsThroughACsvRowInEveryScene) {
  for (Scene scene : {Scene::wall, Scene::pair, Scene::row3, Scene::chain}) {
    Row row;
    row.input = distinctive(scene);
    row.solver = "event-driven";
    row.result.pi1 = 1.0;
    const Row back = parse_row(split_csv(csv_line(row)));
    for (const CaseField& f : kCaseFields) {
      // A field the scene does not use is written empty and read back as the Case default.
      const double expected = used_by(f, scene) ? f.get(row.input) : f.get(Case{});
      EXPECT_EQ(f.get(back.input), expected) << f.name << " in " << name(scene);
    }
    EXPECT_EQ(case_key(back.input), case_key(row.input)) << name(scene);
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
    if (!used_by(f, Scene::chain)) continue;
    Case other = base;
    if (f.integer)
      other.*f.integer += 1;
    else
      other.*f.number *= 1.5;
    EXPECT_NE(case_key(other), case_key(base)) << f.name;
  }
}

}  // namespace
}  // namespace pb
