// The example solver's own tests, in its own folder (built into poundbench_tests with the
// rest): its own setting, `passes`, is checked and changes what a run of a row of three does.
#include <gtest/gtest.h>

#include "kit/testing.hpp"
#include "solvers/registry.hpp"
#include "studies/settings_list.hpp"
#include "solvers/symplectic_euler/symplectic_euler.hpp"

namespace pb {
namespace symplectic_euler_tests {

Settings with_passes(double passes) {
  Settings s;
  s.own[0] = passes;
  return s;
}

TEST(SymplecticEuler, RefusesPassesThatAreNotAWholeNumberFromOneToAHundred) {
  for (double bad : {0.0, 1.5, 101.0, -1.0}) EXPECT_NE(symplectic_euler::check(with_passes(bad)), "") << bad;
  EXPECT_EQ(symplectic_euler::check(with_passes(3)), "");
  EXPECT_EQ(symplectic_euler::check(Settings{}), "");  // not given: one pass
}

TEST(SymplecticEuler, SaysItsPassesInItsSettingsAndItsRegistryRowDeclaresThem) {
  EXPECT_NE(symplectic_euler::describe(with_passes(4)).find("\"passes\":4"), std::string::npos);
  EXPECT_NE(symplectic_euler::describe(Settings{}).find("\"passes\":1"), std::string::npos);
  const SolverInfo* solver = find_solver("symplectic-euler");
  ASSERT_NE(solver, nullptr);
  ASSERT_EQ(solver->own_settings.size(), 1u);
  EXPECT_EQ(solver->own_settings[0].name, "passes");
}

// A settings list takes it as a key, a list of values being an axis of the run's product,
// and refuses it for a solver that does not declare it.
TEST(SymplecticEuler, ASettingsListTakesPassesAsAKeyOfItsOwnSolverAlone) {
  const SettingsList list = parse_settings_list("[[run]]\nsolver = \"symplectic-euler\"\npasses = [1, 3]\nsteps = [32, 64]\n", "own.toml");
  ASSERT_EQ(list.runs.size(), 4u);
  EXPECT_EQ(list.runs[0].settings.own[0], 1.0);
  EXPECT_EQ(list.runs[1].settings.steps, 64);
  EXPECT_EQ(list.runs[2].settings.own[0], 3.0);
  try {
    parse_settings_list("[[run]]\nsolver = \"moreau-jean\"\npasses = 2\n", "own.toml");
    ADD_FAILURE() << "passes accepted for moreau-jean";
  } catch (const SettingsListError& e) {
    EXPECT_NE(std::string(e.what()).find("run[0].passes: not used by solver moreau-jean"), std::string::npos) << e.what();
  }
}

// Where the two contacts of a row of three share body 0 and are closed together (the bodies
// touching at rest), one pass is not the simultaneous impact: more passes change the run (its
// impacts), and every run still ends ok.
TEST(SymplecticEuler, MorePassesChangeARowOfThreeWhoseContactsShareABody) {
  Case c = test::make_case(Scene::row3, PulseShape::cosine, 3.0, 0.5, 0.5);
  c.pi3 = 0.0;
  const System s = make_system(c);
  const Result one = symplectic_euler::solve(s, with_passes(1));
  const Result four = symplectic_euler::solve(s, with_passes(4));
  ASSERT_EQ(one.status, Status::ok) << one.message;
  ASSERT_EQ(four.status, Status::ok) << four.message;
  EXPECT_EQ(symplectic_euler::solve(s, Settings{}).impacts, one.impacts);
  EXPECT_GT(one.impacts, 0);
  EXPECT_NE(four.impacts, one.impacts);
}

// A yielding body is refused by name: this solver's springs are linear.
TEST(SymplecticEuler, RefusesAYieldingCaseByName) {
  const Result r = symplectic_euler::solve(make_system(test::yielding_case(Scene::pair, PulseShape::sine, 1.0, 0.5, 0.5, 0.5, 0.05)), Settings{});
  EXPECT_EQ(r.status, Status::failed);
  EXPECT_EQ(r.message.rfind("yielding: ", 0), 0u) << r.message;
}

}  // namespace symplectic_euler_tests
}  // namespace pb
