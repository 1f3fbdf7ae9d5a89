// Case-set files: expansion, defaults, every kind of bad input, and the shipped sets.

#include "cases/buildings_set.hpp"
#include "cases/case_set.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "cases/system.hpp"
#include "cases/text.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "kit/testing.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace case_set_tests {

constexpr const char* kFile = "sets/x.toml";

// A valid one-case file; tests change one line of it at a time.
const std::string kPair =
    "name = \"t\"\n"
    "[[family]]\n"
    "name = \"a\"\n"
    "scene = \"pair\"\n"
    "pulse = \"sine\"\n"
    "directivity = \"normal\"\n"
    "eps = 0.5\n"
    "pi2 = 1\n"
    "pi3 = 0.5\n"
    "pi5 = 2\n"
    "pi6 = 1\n";

std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("test text lacks " + from);
  return text.replace(at, from.size(), to);
}

std::string without(const std::string& text, const std::string& line) { return with(text, line + "\n", ""); }

CaseSet parse(const std::string& text) { return parse_case_set(text, kFile); }

// kPair with each edit's `from` replaced by its `to`, in turn.
std::string with_all(std::initializer_list<std::pair<std::string, std::string>> edits) {
  std::string text = kPair;
  for (const auto& [from, to] : edits) text = with(text, from, to);
  return text;
}

// 1-based line of the first line holding needle: the line an error about it must name.
int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  if (at == std::string::npos) throw std::logic_error("test text lacks " + needle);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const CaseSetError& e) {
    return e.what();
  }
  return "(no error)";
}

// The message is one line "<file>:<line>: <field>: <reason...>" (line 0: not known).
::testing::AssertionResult fails_with(const std::string& text, int line, const std::string& field,
                                      const std::string& reason) {
  const std::string msg = error_of(text);
  std::string head(kFile);
  if (line > 0) head.append(":").append(std::to_string(line));
  head.append(": ").append(field).append(": ");
  if (msg.rfind(head, 0) != 0)
    return ::testing::AssertionFailure() << "expected \"" << head << "...\", got \"" << msg << "\"";
  if (msg.find(reason, head.size()) == std::string::npos)
    return ::testing::AssertionFailure() << "expected reason \"" << reason << "\", got \"" << msg << "\"";
  if (msg.find('\n') != std::string::npos) return ::testing::AssertionFailure() << "not one line: " << msg;
  return ::testing::AssertionSuccess();
}

// kPair with Pi2 on the grid `{ <grid> }`.
std::string with_pi2_grid(const std::string& grid) { return with(kPair, "pi2 = 1", "pi2 = { " + grid + " }"); }

// kPair with Pi2 on a bad grid fails on Pi2's line, naming family[0].pi2<part>.
::testing::AssertionResult pi2_grid_fails(const std::string& grid, const std::string& part,
                                          const std::string& reason) {
  return fails_with(with_pi2_grid(grid), line_of(kPair, "pi2 ="), "family[0].pi2" + part, reason);
}

// --- expansion ------------------------------------------------------------------------

TEST(CaseSetExpansion, ExpandsTheCartesianProductWithPi2Innermost) {
  const CaseSet set = parse(with_all({{"pulse = \"sine\"", "pulse = [\"sine\", \"cosine\"]"},
                                      {"pi5 = 2", "pi5 = [0.5, 2]"},
                                      {"pi2 = 1", "pi2 = [1, 2, 3]"}}));
  ASSERT_EQ(set.cases.size(), 12u);
  // pulse outer, then pi5, then pi2 innermost.
  for (std::size_t i = 0; i < set.cases.size(); ++i) {
    const Case& c = set.cases[i];
    EXPECT_EQ(c.pulse, i < 6 ? PulseShape::sine : PulseShape::cosine) << i;
    EXPECT_EQ(c.pi5, (i / 3) % 2 == 0 ? 0.5 : 2.0) << i;
    EXPECT_EQ(c.pi2, static_cast<double>(i % 3 + 1)) << i;
    EXPECT_EQ(c.family, "a");
  }
}

TEST(CaseSetExpansion, OrdersSceneOutermostThenDirectivityEpsAndGap) {
  const std::string text =
      "name = \"t\"\n[[family]]\nname = \"a\"\nscene = [\"wall\", \"pair\"]\npulse = \"sine\"\n"
      "directivity = [\"normal\", \"reverse\"]\neps = [0, 1]\npi3 = [0, 0.5]\npi2 = [1, 2]\n"
      "pi5 = 2\npi6 = 1\n";
  const CaseSet set = parse(text);
  ASSERT_EQ(set.cases.size(), 32u);
  for (std::size_t i = 0; i < 32; ++i) {
    const Case& c = set.cases[i];
    EXPECT_EQ(c.scene, i < 16 ? Scene::wall : Scene::pair) << i;
    EXPECT_EQ(c.directivity, (i / 8) % 2 == 0 ? Directivity::normal : Directivity::reverse) << i;
    EXPECT_EQ(c.eps, (i / 4) % 2 == 0 ? 0.0 : 1.0) << i;
    EXPECT_EQ(c.pi3, (i / 2) % 2 == 0 ? 0.0 : 0.5) << i;
    EXPECT_EQ(c.pi2, i % 2 == 0 ? 1.0 : 2.0) << i;
  }
}

TEST(CaseSetExpansion, KeysAModelDoesNotUseDoNotMultiplyItsCases) {
  // wall has no body 1: its cases must not repeat over the pi5 list.
  const CaseSet set =
      parse(with_all({{"scene = \"pair\"", "scene = [\"wall\", \"pair\"]"}, {"pi5 = 2", "pi5 = [0.5, 2, 4]"}}));
  ASSERT_EQ(set.cases.size(), 4u);
  EXPECT_EQ(set.cases[0].scene, Scene::wall);
  EXPECT_EQ(set.cases[1].scene, Scene::pair);
  EXPECT_EQ(set.cases[3].pi5, 4.0);
}

TEST(CaseSetExpansion, LogGridHasExactEndsAndConstantRatio) {
  const std::string text = with_pi2_grid("from = 0.1, to = 10, points = 200, spacing = \"log\"");
  const CaseSet set = parse(text);
  ASSERT_EQ(set.cases.size(), 200u);
  EXPECT_EQ(set.cases.front().pi2, 0.1);  // exactly as written
  EXPECT_EQ(set.cases.back().pi2, 10.0);
  const double ratio = std::pow(100.0, 1.0 / 199.0);
  // exp/log of values of order 1 err by a few ulps: 1e-12 leaves a wide margin yet would
  // catch a wrong step (the next-closest grid, 201 points, differs by 1e-4 in the ratio).
  for (std::size_t i = 1; i < 200; ++i)
    EXPECT_NEAR(set.cases[i].pi2 / set.cases[i - 1].pi2, ratio, 1e-12) << i;
}

TEST(CaseSetExpansion, LinearGridHasExactEndsAndConstantStep) {
  const std::string text =
      with(kPair, "eps = 0.5", "eps = { from = 0, to = 1, points = 11, spacing = \"linear\" }");
  const CaseSet set = parse(text);
  ASSERT_EQ(set.cases.size(), 11u);
  EXPECT_EQ(set.cases.front().eps, 0.0);
  EXPECT_EQ(set.cases.back().eps, 1.0);
  for (std::size_t i = 1; i < 11; ++i)  // rounding of k/10 only: a few ulps of 1
    EXPECT_NEAR(set.cases[i].eps - set.cases[i - 1].eps, 0.1, 1e-15) << i;
}

TEST(CaseSetExpansion, OnePointGridIsItsEnd) {
  const std::string text = with_pi2_grid("from = 3, to = 3, points = 1, spacing = \"log\"");
  const CaseSet set = parse(text);
  ASSERT_EQ(set.cases.size(), 1u);
  EXPECT_EQ(set.cases[0].pi2, 3.0);
}

TEST(CaseSetExpansion, SymmetricRowCopiesBody1IntoBody2) {
  const CaseSet set = parse(with_all({{"scene = \"pair\"", "scene = \"row3\"\nsymmetric = true"},
                                      {"pi5 = 2", "pi5 = [0.5, 2]"},
                                      {"pi6 = 1", "pi6 = 3"}}));
  ASSERT_EQ(set.cases.size(), 2u);
  for (const Case& c : set.cases) {
    EXPECT_EQ(c.scene, Scene::row3);
    EXPECT_EQ(c.pi7, c.pi5);
    EXPECT_EQ(c.pi8, 3.0);
  }
  EXPECT_EQ(set.cases[1].pi7, 2.0);
}

TEST(CaseSetExpansion, AsymmetricRowTakesItsOwnBody2) {
  const std::string text =
      with(kPair, "scene = \"pair\"", "scene = \"row3\"\npi7 = [4, 5]\npi8 = 0.25\nsymmetric = false");
  const CaseSet set = parse(text);
  ASSERT_EQ(set.cases.size(), 2u);
  EXPECT_EQ(set.cases[0].pi7, 4.0);
  EXPECT_EQ(set.cases[1].pi7, 5.0);
  EXPECT_EQ(set.cases[1].pi8, 0.25);
  EXPECT_EQ(set.cases[1].pi5, 2.0);
}

// A chain takes its body count (and a kick) on top of pair's keys.
std::string chain_of(const std::string& bodies_line) {
  return with(kPair, "scene = \"pair\"", "scene = \"chain\"\n" + bodies_line);
}

TEST(CaseSetChain, ExpandsBodiesAndKickOutsideThePulseAndDefaultsKickToZero) {
  const CaseSet set =
      parse(with(chain_of("bodies = [2, 5]\nkick = [0, 1.5]"), "pulse = \"sine\"", "pulse = [\"sine\", \"cosine\"]"));
  ASSERT_EQ(set.cases.size(), 8u);
  for (std::size_t i = 0; i < set.cases.size(); ++i) {
    const Case& c = set.cases[i];
    EXPECT_EQ(c.scene, Scene::chain);
    EXPECT_EQ(c.bodies, i < 4 ? 2 : 5) << i;  // bodies outermost after the scene
    EXPECT_EQ(c.kick, (i / 2) % 2 == 0 ? 0.0 : 1.5) << i;
    EXPECT_EQ(c.pulse, i % 2 == 0 ? PulseShape::sine : PulseShape::cosine) << i;
    EXPECT_EQ(c.pi5, 2.0);  // pi5/pi6 describe the odd bodies
    EXPECT_EQ(validate(c), std::nullopt);
  }
  const CaseSet still = parse(chain_of("bodies = 3"));
  ASSERT_EQ(still.cases.size(), 1u);
  EXPECT_EQ(still.cases[0].bodies, 3);
  EXPECT_EQ(still.cases[0].kick, 0.0);
}

TEST(CaseSetChain, BodiesMayBeALinearGridOfWholeNumbers) {
  const CaseSet set = parse(chain_of("bodies = { from = 2, to = 20, points = 10, spacing = \"linear\" }"));
  ASSERT_EQ(set.cases.size(), 10u);
  for (std::size_t i = 0; i < set.cases.size(); ++i) EXPECT_EQ(set.cases[i].bodies, 2 + 2 * static_cast<int>(i));
}

TEST(CaseSetChain, MixedScenesGiveTheChainKeysToTheChainOnly) {
  const CaseSet set =
      parse(with(kPair, "scene = \"pair\"", "scene = [\"wall\", \"pair\", \"chain\"]\nbodies = [4, 6]\nkick = 1"));
  ASSERT_EQ(set.cases.size(), 4u);  // wall, pair, chain of 4, chain of 6
  EXPECT_EQ(set.cases[0].bodies, 0);
  EXPECT_EQ(set.cases[1].kick, 0.0);
  EXPECT_EQ(set.cases[3].bodies, 6);
  EXPECT_EQ(set.cases[3].kick, 1.0);
}

TEST(CaseSetChain, ABodyCountOrKickForAnotherSceneIsRejected) {
  EXPECT_TRUE(fails_with(kPair + "bodies = 5\n", 12, "family[0].bodies", "not used by scene pair"));
  EXPECT_TRUE(fails_with(kPair + "kick = 1\n", 12, "family[0].kick", "describe a chain only"));
  // A default serves the families that have a chain and is ignored by the others.
  const CaseSet set = parse(with(kPair, "[[family]]", "[defaults]\nbodies = 7\nkick = 2\n[[family]]"));
  ASSERT_EQ(set.cases.size(), 1u);
  EXPECT_EQ(set.cases[0].bodies, 0);
}

TEST(CaseSetChain, BadBodyCountsNameTheFieldTheLineAndTheValue) {
  const int family = line_of(kPair, "[[family]]");
  EXPECT_TRUE(fails_with(chain_of(""), family, "family[0].bodies", "required by scene chain"));
  EXPECT_TRUE(fails_with(chain_of("bodies = 1"), 5, "family[0].bodies", "2 to 1000 bodies (got 1)"));
  EXPECT_TRUE(fails_with(chain_of("bodies = 1e9"), 5, "family[0].bodies", "(got 1e+09)"));
  EXPECT_TRUE(fails_with(chain_of("bodies = [4, 2.5]"), 5, "family[0].bodies[1]", "whole number (got 2.5)"));
  EXPECT_TRUE(fails_with(chain_of("bodies = { from = 2, to = 100, points = 6, spacing = \"log\" }"), 5,
                         "family[0].bodies", "whole number"));
  EXPECT_TRUE(fails_with(chain_of("bodies = \"many\""), 5, "family[0].bodies", "must be a number"));
  EXPECT_TRUE(fails_with(chain_of("bodies = 4\nkick = inf"), 6, "family[0].kick", "must be finite"));
  EXPECT_TRUE(fails_with(without(chain_of("bodies = 4"), "pi6 = 1"), family, "family[0].pi6",
                         "required by scene chain"));
  EXPECT_TRUE(fails_with(chain_of("bodies = 4") + "pi7 = 1\n", 13, "family[0].pi7", "not used by scene chain"));
}

// --- defaults ---------------------------------------------------------------------------

TEST(CaseSetDefaults, UnstatedDampingDurationAndScaleTakeTheSpecDefaults) {
  const CaseSet set = parse(kPair);
  ASSERT_EQ(set.cases.size(), 1u);
  const Case& c = set.cases[0];
  EXPECT_EQ(set.name, "t");
  EXPECT_EQ(set.description, "");
  EXPECT_EQ(c.xi, 0.05);
  EXPECT_EQ(c.n_free, 3.0);
  EXPECT_EQ(c.a_p, 1.0);
  EXPECT_EQ(c.w_p, 1.0);
  EXPECT_EQ(c.eps, 0.5);
  EXPECT_EQ(c.pi3, 0.5);
  EXPECT_EQ(c.pi6, 1.0);
}

TEST(CaseSetDefaults, FamilyKeysOverrideDefaultsWhichOverrideBuiltIns) {
  const std::string text =
      "name = \"t\"\ndescription = \"d\"\n[defaults]\nxi = 0.02\neps = 1\npi5 = 7\npi6 = 2\n"
      "pulse = \"cosine\"\ndirectivity = \"reverse\"\npi2 = 1\npi3 = 0\n"
      "[[family]]\nname = \"a\"\nscene = \"pair\"\neps = 0\n"
      "[[family]]\nname = \"b\"\nscene = \"wall\"\nn_free = 5\n";  // wall ignores the default pi5/pi6
  const CaseSet set = parse(text);
  EXPECT_EQ(set.description, "d");
  ASSERT_EQ(set.cases.size(), 2u);
  const Case& a = set.cases[0];
  EXPECT_EQ(a.family, "a");
  EXPECT_EQ(a.xi, 0.02);
  EXPECT_EQ(a.eps, 0.0);
  EXPECT_EQ(a.pi5, 7.0);
  EXPECT_EQ(a.pulse, PulseShape::cosine);
  EXPECT_EQ(a.directivity, Directivity::reverse);
  const Case& b = set.cases[1];
  EXPECT_EQ(b.family, "b");
  EXPECT_EQ(b.scene, Scene::wall);
  EXPECT_EQ(b.eps, 1.0);
  EXPECT_EQ(b.n_free, 5.0);
  EXPECT_EQ(b.pi3, 0.0);
}

TEST(CaseSetDefaults, FamilySymmetryOverridesADefaultBody2) {
  const CaseSet set = parse(with_all({{"[[family]]", "[defaults]\npi7 = 9\npi8 = 9\n[[family]]"},
                                      {"scene = \"pair\"", "scene = \"row3\"\nsymmetric = true"},
                                      {"pi6 = 1", "pi6 = 3"}}));
  ASSERT_EQ(set.cases.size(), 1u);
  EXPECT_EQ(set.cases[0].pi7, 2.0);
  EXPECT_EQ(set.cases[0].pi8, 3.0);
}

// --- bad input ---------------------------------------------------------------------------

TEST(CaseSetErrors, MalformedTomlNamesTheLine) {
  EXPECT_TRUE(fails_with(with(kPair, "pi5 = 2", "pi5 = = 2"), line_of(kPair, "pi5 ="), "syntax", ""));
  EXPECT_TRUE(fails_with(kPair + "pi6 = 2\n", 12, "syntax", "redefin"));
}

TEST(CaseSetErrors, UnknownKeysAnywhereAreRejectedWithASuggestion) {
  EXPECT_TRUE(fails_with(with(kPair, "pi6 = 1", "pi6 = 1\npi55 = 1"), 12, "family[0].pi55",
                         "unknown key (did you mean pi5?)"));
  EXPECT_TRUE(fails_with(with(kPair, "eps = 0.5", "pi4 = 0.5"), line_of(kPair, "eps"), "family[0].pi4",
                         "Pi4 is written eps"));
  EXPECT_TRUE(fails_with("titel = \"x\"\n" + kPair, 1, "titel", "unknown key"));
  EXPECT_TRUE(fails_with(with(kPair, "[[family]]", "[defaults]\nksi = 0.1\n[[family]]"), 3, "defaults.ksi",
                         "did you mean xi?"));
  EXPECT_TRUE(fails_with(with(kPair, "[[family]]", "[defaults]\nname = \"x\"\n[[family]]"), 3, "defaults.name",
                         "not allowed in [defaults]"));
  EXPECT_TRUE(pi2_grid_fails("from = 1, to = 2, points = 3, spacing = \"log\", step = 1", ".step", "unknown key"));
}

TEST(CaseSetErrors, MissingRequiredFieldsAreNamed) {
  const int family = line_of(kPair, "[[family]]");
  EXPECT_TRUE(fails_with(without(kPair, "eps = 0.5"), family, "family[0].eps", "required"));
  EXPECT_TRUE(fails_with(without(kPair, "scene = \"pair\""), family, "family[0].scene", "required"));
  EXPECT_TRUE(fails_with(without(kPair, "pulse = \"sine\""), family, "family[0].pulse", "required"));
  EXPECT_TRUE(fails_with(without(kPair, "directivity = \"normal\""), family, "family[0].directivity", "required"));
  EXPECT_TRUE(fails_with(without(kPair, "pi2 = 1"), family, "family[0].pi2", "required"));
  EXPECT_TRUE(fails_with(without(kPair, "pi3 = 0.5"), family, "family[0].pi3", "required"));
  EXPECT_TRUE(fails_with(without(kPair, "pi5 = 2"), family, "family[0].pi5", "required by scene pair"));
  EXPECT_TRUE(fails_with(without(kPair, "pi6 = 1"), family, "family[0].pi6", "required by scene pair"));
  EXPECT_TRUE(fails_with(with(kPair, "scene = \"pair\"", "scene = \"row3\""), family, "family[0].pi7",
                         "required by scene row3"));
  EXPECT_TRUE(fails_with(without(kPair, "name = \"a\""), family, "family[0].name", "required"));
  EXPECT_TRUE(fails_with(without(kPair, "name = \"t\""), 0, "name", "required"));
}

TEST(CaseSetErrors, WrongTypesAreNamed) {
  EXPECT_TRUE(fails_with(with(kPair, "pi5 = 2", "pi5 = \"2\""), 10, "family[0].pi5",
                         "must be a number, a list of numbers or a grid"));
  EXPECT_TRUE(fails_with(with(kPair, "pi5 = 2", "pi5 = [1, \"2\"]"), 10, "family[0].pi5[1]",
                         "must be a number, got a string"));
  EXPECT_TRUE(fails_with(with(kPair, "scene = \"pair\"", "scene = 3"), 4, "family[0].scene",
                         "must be a string or a list of strings"));
  EXPECT_TRUE(fails_with(with(kPair, "scene = \"pair\"", "scene = \"row3\"\nsymmetric = \"yes\""), 5,
                         "family[0].symmetric", "must be true or false"));
  EXPECT_TRUE(fails_with(with(kPair, "name = \"a\"", "name = 1"), 3, "family[0].name", "must be a string"));
  EXPECT_TRUE(fails_with(with(kPair, "name = \"a\"", "name = \"a b\""), 3, "family[0].name", "may hold only"));
  EXPECT_TRUE(fails_with(with(kPair, "[[family]]", "[family]"), 2, "family", "must be an array of tables"));
  EXPECT_TRUE(pi2_grid_fails("from = 1, to = 2, points = 2.5, spacing = \"log\"", ".points", "must be an integer"));
  EXPECT_TRUE(
      pi2_grid_fails("from = 1, to = 2, points = 2, spacing = \"cubic\"", ".spacing", "must be \"log\" or \"linear\""));
}

TEST(CaseSetErrors, OutOfRangeValuesNameTheFieldTheLineAndTheValue) {
  EXPECT_TRUE(fails_with(with(kPair, "pi2 = 1", "pi2 = inf"), 8, "family[0].pi2", "must be finite and > 0"));
  EXPECT_TRUE(fails_with(with(kPair, "pi2 = 1", "pi2 = nan"), 8, "family[0].pi2", "must be finite"));
  EXPECT_TRUE(fails_with(with(kPair, "pi2 = 1", "pi2 = 0"), 8, "family[0].pi2", "> 0 (got 0)"));
  EXPECT_TRUE(fails_with(with(kPair, "pi3 = 0.5", "pi3 = -0.1"), 9, "family[0].pi3", ">= 0 (got -0.1)"));
  EXPECT_TRUE(fails_with(with(kPair, "eps = 0.5", "eps = 1.5"), 7, "family[0].eps", "[0, 1] (got 1.5)"));
  EXPECT_TRUE(fails_with(with(kPair, "pi5 = 2", "pi5 = -1"), 10, "family[0].pi5", "frequency ratio"));
  EXPECT_TRUE(fails_with(with(kPair, "pi6 = 1", "pi6 = 0"), 11, "family[0].pi6", "mass ratio"));
  EXPECT_TRUE(fails_with(kPair + "xi = 1\n", 12, "family[0].xi", "[0, 1) (got 1)"));
  EXPECT_TRUE(fails_with(kPair + "xi = -0.01\n", 12, "family[0].xi", "damping ratio"));
  EXPECT_TRUE(fails_with(kPair + "n_free = 0\n", 12, "family[0].n_free", "> 0"));
  EXPECT_TRUE(fails_with(kPair + "a_p = -9.81\n", 12, "family[0].a_p", "> 0"));
  EXPECT_TRUE(fails_with(kPair + "w_p = 0\n", 12, "family[0].w_p", "> 0"));
  // A bad element of a multi-line list: the element's own line and index.
  EXPECT_TRUE(fails_with(with(kPair, "pi5 = 2", "pi5 = [\n  1,\n  -2,\n]"), 12, "family[0].pi5[1]",
                         "got -2"));
  // A bad value in [defaults] points at [defaults].
  EXPECT_TRUE(fails_with(with(without(kPair, "eps = 0.5"), "[[family]]", "[defaults]\neps = 2\n[[family]]"),
                         3, "defaults.eps", "[0, 1]"));
}

TEST(CaseSetErrors, EmptyListsAndGridsAreRejected) {
  EXPECT_TRUE(fails_with(with(kPair, "pi5 = 2", "pi5 = []"), 10, "family[0].pi5", "empty list"));
  EXPECT_TRUE(fails_with(with(kPair, "pulse = \"sine\"", "pulse = []"), 5, "family[0].pulse", "empty list"));
  EXPECT_TRUE(pi2_grid_fails("from = 1, to = 2, points = 0, spacing = \"log\"", ".points", "must be >= 1"));
  EXPECT_TRUE(pi2_grid_fails("from = 0, to = 2, points = 5, spacing = \"log\"", "", "log grid needs from > 0"));
  EXPECT_TRUE(pi2_grid_fails("from = 1, to = 2, points = 1, spacing = \"log\"", "", "1 point needs from == to"));
  EXPECT_TRUE(pi2_grid_fails("to = 2, points = 3, spacing = \"log\"", ".from", "required"));
}

TEST(CaseSetErrors, UnknownSceneuPulseAndDirectivityNamesAreRejected) {
  EXPECT_TRUE(fails_with(with(kPair, "scene = \"pair\"", "scene = \"row4\""), 4, "family[0].scene",
                         "unknown scene \"row4\""));
  EXPECT_TRUE(fails_with(with(kPair, "pulse = \"sine\"", "pulse = [\"sine\", \"square\"]"), 5,
                         "family[0].pulse[1]", "unknown pulse \"square\""));
  EXPECT_TRUE(fails_with(with(kPair, "directivity = \"normal\"", "directivity = \"forward\""), 6,
                         "family[0].directivity", "unknown directivity"));
}

TEST(CaseSetErrors, KeysTheScenesDoNotUseAreRejected) {
  EXPECT_TRUE(fails_with(kPair + "pi7 = 2\n", 12, "family[0].pi7", "not used by scene pair"));
  EXPECT_TRUE(fails_with(kPair + "symmetric = true\n", 12, "family[0].symmetric", "not used by scene pair"));
  EXPECT_TRUE(fails_with(with(without(kPair, "pi6 = 1"), "scene = \"pair\"", "scene = \"wall\""), 10,
                         "family[0].pi5", "not used by scene wall"));
  EXPECT_TRUE(fails_with(with(kPair, "scene = \"pair\"", "scene = \"row3\"\nsymmetric = true\npi8 = 2"), 6,
                         "family[0].pi8", "not allowed with symmetric = true (line 5)"));
}

TEST(CaseSetErrors, DuplicateFamilyNamesAndMissingFamiliesAreRejected) {
  const std::string twice = kPair + kPair.substr(kPair.find("[[family]]"));
  EXPECT_TRUE(fails_with(twice, 13, "family[1].name", "duplicate family name \"a\" (first used at line 3)"));
  EXPECT_TRUE(fails_with("name = \"t\"\n", 0, "family", "no [[family]] tables"));
  EXPECT_TRUE(fails_with("name = \"t\"\nfamily = []\n", 2, "family", "the list is empty"));
  EXPECT_TRUE(fails_with("name = \"t\"\nfamily = [1]\n", 2, "family[0]", "must be a table"));
}

TEST(CaseSetErrors, AMissingFileSaysItCannotBeRead) {
  const std::string path = std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/no-such-set.toml";
  try {
    load_case_set(path);
    FAIL() << "loaded a missing file";
  } catch (const CaseSetError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot read: No such file or directory");
  }
}

// --- the valid domain (cases/README.md) -------------------------------------------------

// A pair whose frequencies span the whole allowed contrast: body 0 at w_p, body 1 at
// w_p / 1e4 or 1e4 w_p; masses 1e6 apart.
Case corner_pair(double pi5, double pi6) {
  Case c;
  c.scene = Scene::pair;
  c.pi2 = 1.0;
  c.pi5 = pi5;
  c.pi6 = pi6;
  return c;
}

TEST(CaseDomain, TheCornersOfTheDomainAreAccepted) {
  for (double pi5 : {kMaxFrequencyContrast, 1.0 / kMaxFrequencyContrast})
    for (double pi6 : {kMaxMassContrast, 1.0 / kMaxMassContrast}) {
      Case c = corner_pair(pi5, pi6);
      EXPECT_EQ(validate(c), std::nullopt) << pi5 << " " << pi6;
      for (double a_p : {kMinAp, kMaxAp})
        for (double w_p : {kMinWp, kMaxWp}) {
          c.a_p = a_p;
          c.w_p = w_p;
          EXPECT_EQ(validate(c), std::nullopt) << a_p << " " << w_p;
        }
    }
  Case c = corner_pair(2.0, 1.0);
  c.pi3 = kMaxPi3;
  c.n_free = 99;  // the most free periods that every contrast allows
  c.pi2 = kMaxFrequencyContrast;
  c.pi5 = kMaxFrequencyContrast;  // body 1 at w_p: the widest span with n_free = 99
  EXPECT_EQ(validate(c), std::nullopt);
  c.pi2 = 1.0;
  c.pi5 = 2.0;
  c.n_free = kMaxNFree;
  EXPECT_EQ(validate(c), std::nullopt);
  Case chain;
  chain.scene = Scene::chain;
  chain.bodies = kMaxChainBodies;
  chain.kick = -kMaxKick;
  EXPECT_EQ(validate(chain), std::nullopt);
}

// What lies outside names its field and its bound.
::testing::AssertionResult refused(const Case& c, const std::string& field, const std::string& bound) {
  const std::optional<std::string> bad = validate(c);
  if (!bad) return ::testing::AssertionFailure() << "accepted";
  if (bad->rfind(field + ": ", 0) != 0 || bad->find(bound) == std::string::npos)
    return ::testing::AssertionFailure() << "expected " << field << ": ..." << bound << "..., got " << *bad;
  return ::testing::AssertionSuccess();
}

TEST(CaseDomain, InputsBeyondTheDomainAreRefusedNamingTheBound) {
  const Case pair = corner_pair(0.5, 1.0);
  auto with_value = [&](double Case::*field, double value) {
    Case c = pair;
    c.*field = value;
    return c;
  };
  EXPECT_TRUE(refused(with_value(&Case::pi2, 1e-100), "pi2", "more than 1e4"));
  EXPECT_TRUE(refused(with_value(&Case::pi2, 2e4), "pi2", "more than 1e4"));
  EXPECT_TRUE(refused(with_value(&Case::pi5, 1e308), "pi5", "more than 1e4"));
  EXPECT_TRUE(refused(with_value(&Case::pi5, 1e-300), "pi5", "more than 1e4"));
  // Within 1e4 of body 0 but 1e5 away from w_p.
  Case spread = pair;
  spread.pi2 = 10.0;
  spread.pi5 = 1e-4;
  EXPECT_TRUE(refused(spread, "pi5", "contrast (max/min) of 1e5, more than 1e4"));
  EXPECT_TRUE(refused(with_value(&Case::pi6, 1e-300), "pi6", "more than 1e6"));
  EXPECT_TRUE(refused(with_value(&Case::pi6, 1e308), "pi6", "more than 1e6"));
  EXPECT_TRUE(refused(with_value(&Case::pi3, 2e6), "pi3", "<= 1e6"));
  EXPECT_TRUE(refused(with_value(&Case::n_free, 1e308), "n_free", "<= 1000"));
  EXPECT_TRUE(refused(with_value(&Case::a_p, 1e200), "a_p", "[1e-12, 1e12]"));
  EXPECT_TRUE(refused(with_value(&Case::a_p, 1e-300), "a_p", "[1e-12, 1e12]"));
  EXPECT_TRUE(refused(with_value(&Case::w_p, 1e100), "w_p", "[1e-6, 1e6]"));
  EXPECT_TRUE(refused(with_value(&Case::w_p, 1e-300), "w_p", "[1e-6, 1e6]"));
  // Each bound alone is met, but the run would be 1e7 shortest periods long.
  Case slow = with_value(&Case::n_free, kMaxNFree);
  slow.pi5 = 1e3;
  EXPECT_TRUE(refused(slow, "n_free", "more than 1e6"));
  Case row = pair;
  row.scene = Scene::row3;
  row.pi7 = 1e5;
  EXPECT_TRUE(refused(row, "pi7", "more than 1e4"));
  row.pi7 = 1.0;
  row.pi8 = 1e7;
  EXPECT_TRUE(refused(row, "pi8", "more than 1e6"));
  Case chain;
  chain.scene = Scene::chain;
  chain.bodies = 3;
  chain.pi6 = 1e7;  // the odd bodies of a chain take pi5 and pi6
  EXPECT_TRUE(refused(chain, "pi6", "more than 1e6"));
  chain.pi6 = 1.0;
  chain.kick = 1e7;
  EXPECT_TRUE(refused(chain, "kick", "1e6"));
}

TEST(CaseDomain, ACaseSetValueBeyondTheDomainNamesItsLineAndValue) {
  EXPECT_TRUE(fails_with(with(kPair, "pi5 = 2", "pi5 = [2, 1e5]"), 10, "family[0].pi5[1]",
                         "more than 1e4 (got 100000)"));
  EXPECT_TRUE(fails_with(kPair + "w_p = 1e100\n", 12, "family[0].w_p", "[1e-6, 1e6] (got 1e+100)"));
  EXPECT_TRUE(fails_with(kPair + "n_free = 1e308\n", 12, "family[0].n_free", "<= 1000"));
}

TEST(CaseDomain, Pi1IsSelfSimilarAtTheCornersOfThePulseScales) {
  const SolverInfo& reference = *find_solver("event-driven");
  const Case c = test::make_case(Scene::pair, PulseShape::cosine, 0.8, 0.5, 0.5);  // the README's pair case
  const Result unit = reference.solve(make_system(c), Settings{});
  ASSERT_EQ(unit.status, Status::ok) << unit.message;
  ASSERT_GT(unit.impacts, 0);
  for (double a_p : {kMinAp, kMaxAp})
    for (double w_p : {kMinWp, kMaxWp}) {
      Case scaled = c;
      scaled.a_p = a_p;
      scaled.w_p = w_p;
      ASSERT_EQ(validate(scaled), std::nullopt);
      const Result r = reference.solve(make_system(scaled), Settings{});
      EXPECT_EQ(r.status, Status::ok) << a_p << " " << w_p << ": " << r.message;
      EXPECT_NEAR(r.pi1, unit.pi1, 1e-9 * unit.pi1) << a_p << " " << w_p;
      EXPECT_EQ(r.impacts, unit.impacts) << a_p << " " << w_p;
    }
}

// At the contrast corners the reference either reaches t_end with a finite Pi1 or says it
// stopped. A light body 0 against a heavy, soft body 1 with eps = 1 rattles against it
// for the whole run (measured: over 1e6 events); that is the physics, and the event cap
// reports it.
TEST(CaseDomain, TheReferenceEndsAtTheContrastCornersReachingTEndOrSayingWhy) {
  const SolverInfo& reference = *find_solver("event-driven");
  Settings capped;
  capped.step_cap = 100'000;
  int reached = 0;
  for (double pi5 : {kMaxFrequencyContrast, 1.0 / kMaxFrequencyContrast})
    for (double pi6 : {kMaxMassContrast, 1.0 / kMaxMassContrast})
      for (double eps : {0.0, 1.0}) {
        Case c = corner_pair(pi5, pi6);
        c.eps = eps;
        const Result r = reference.solve(make_system(c), capped);
        const std::string label = std::to_string(pi5) + " " + std::to_string(pi6) + " " + std::to_string(eps);
        EXPECT_TRUE(r.status == Status::ok || r.status == Status::step_cap) << label << ": " << r.message;
        if (r.status != Status::ok) continue;
        ++reached;
        EXPECT_TRUE(std::isfinite(r.pi1) && r.pi1 > 0.0) << label;
      }
  EXPECT_GE(reached, 6);  // measured: all but the two rattling corners
}

TEST(CaseDomain, ClipShortensLongUserTextAtACharacterBoundary) {
  EXPECT_EQ(clip("pi5"), "pi5");
  EXPECT_EQ(clip(std::string(kMaxEchoed, 'k')), std::string(kMaxEchoed, 'k'));
  EXPECT_EQ(clip(std::string(10'000'000, 'k')), std::string(kMaxEchoed, 'k') + "...");
  EXPECT_EQ(clip("ab\xC3\xA9" "cd", 3), "ab...");  // never half of the two-byte e-acute
}

TEST(CaseDomain, AHugeUnknownKeyIsEchoedClipped) {
  const std::string key(10'000'000, 'k');
  const std::string msg = error_of(with(kPair, "pi6 = 1", "pi6 = 1\n" + key + " = 1"));
  EXPECT_LE(msg.size(), 300u) << msg.substr(0, 340);  // one line, as every error: the list is cut at 140 characters
  EXPECT_NE(msg.find("family[0]." + std::string(kMaxEchoed, 'k') + "...: unknown key"), std::string::npos)
      << msg.substr(0, 300);
  const std::string value(1'000'000, 'v');
  const std::string bad_scene = error_of(with(kPair, "scene = \"pair\"", "scene = \"" + value + "\""));
  EXPECT_LT(bad_scene.size(), 300u);
  EXPECT_NE(bad_scene.find("unknown scene"), std::string::npos) << bad_scene.substr(0, 300);
}

// --- the shipped sets ---------------------------------------------------------------------

std::map<std::string, std::size_t> count_by_family(const CaseSet& set) {
  std::map<std::string, std::size_t> n;
  for (const Case& c : set.cases) ++n[c.family];
  return n;
}

TEST(ShippedCaseSets, PaperSetLoadsWithTheExpectedPointCounts) {
  const CaseSet set = load_case_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/paper.toml");
  EXPECT_EQ(set.name, "paper");
  const std::map<std::string, std::size_t> expected = {
      {"fig3", 3 * 200},          {"fig4-flexible", 2 * 4 * 200}, {"fig4-stiff", 2 * 4 * 200},
      {"fig5-flexible", 2 * 4 * 200}, {"fig5-stiff", 2 * 4 * 200}, {"fig7", 2 * 8 * 200},
      {"fig8", 2 * 2 * 7 * 200},  {"fig9", 2 * 2 * 7 * 200},      {"fig10", 2 * 2 * 41 * 5},
      {"eps-cover", 2 * 2 * 2 * 200}};
  EXPECT_EQ(count_by_family(set), expected);
  EXPECT_EQ(set.cases.size(), 23820u);
  for (const Case& c : set.cases) {
    EXPECT_EQ(validate(c), std::nullopt) << c.family;
    EXPECT_EQ(c.xi, 0.05);
    if (c.family != "eps-cover") {
      EXPECT_EQ(c.eps, 0.5) << c.family;
    }
    if (c.family == "fig7") {
      EXPECT_TRUE(c.pi7 == c.pi5 && c.pi8 == c.pi6);
    }
  }
}

TEST(ShippedCaseSets, SmokeSetIsSmallAndCoversEveryClass) {
  const CaseSet set = load_case_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/smoke.toml");
  EXPECT_EQ(set.cases.size(), 40u);
  std::map<std::string, int> seen;
  bool symmetric_row = false, asymmetric_row = false;
  for (const Case& c : set.cases) {
    EXPECT_EQ(validate(c), std::nullopt) << c.family;
    ++seen[std::string(name(c.scene))];
    ++seen[std::string(name(c.pulse))];
    ++seen[std::string(name(c.directivity))];
    ++seen["eps=" + std::to_string(c.eps)];
    if (c.pi3 == 0.0) ++seen["touching"];
    if (c.scene == Scene::row3) (c.pi7 == c.pi5 && c.pi8 == c.pi6 ? symmetric_row : asymmetric_row) = true;
  }
  for (const char* k : {"wall", "pair", "row3", "sine", "cosine", "normal", "reverse", "eps=0.000000",
                        "eps=0.500000", "eps=1.000000", "touching"})
    EXPECT_GT(seen[k], 0) << k;
  EXPECT_TRUE(symmetric_row);
  EXPECT_TRUE(asymmetric_row);
}

// Every shipped set lies inside the valid domain (loading validates every case), with
// its widest contrasts: stress reaches 1e3 in frequency and 1e2 in mass.
TEST(ShippedCaseSets, EveryShippedSetLiesInsideTheValidDomain) {
  std::size_t sets = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets")) {
    if (entry.path().extension() != ".toml") continue;
    ++sets;
    // A set of the buildings scene has its own reader, which validates every point.
    std::optional<BuildingsSet> buildings;
    EXPECT_NO_THROW(buildings = load_buildings_set(entry.path())) << entry.path();
    if (buildings) {
      EXPECT_FALSE(buildings->points.empty()) << entry.path();
      continue;
    }
    CaseSet set;
    EXPECT_NO_THROW(set = load_case_set(entry.path())) << entry.path();
    EXPECT_FALSE(set.cases.empty()) << entry.path();
  }
  EXPECT_GE(sets, 6u);
}

}  // namespace case_set_tests
}  // namespace pb
