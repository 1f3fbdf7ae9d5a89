// The external solver on the buildings scene (solvers/external/buildings.cpp,
// programs/buildings_protocol.hpp): the case document carries the model poundbench solves,
// number for number (C as the solvers' own, the step as the time-steppers plan it); an answer
// becomes the BuildingsResult it says, per point and persistent; a malformed answer is refused
// in one line naming its field, and every other way a program goes wrong is a result as for the
// single oscillators.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/testing_buildings.hpp"
#include "programs/buildings_protocol.hpp"
#include "solvers/external/external.hpp"
#include "solvers/registry.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace external_buildings_tests {

using buildings::BuildingsResult;
using Json = nlohmann::json;

// A program that answers `answer` (one line of JSON, no single quotes) whatever it is asked.
std::string answering(const std::string& answer) { return "sh -c 'cat > /dev/null; echo \"$0\"' '" + answer + "'"; }

// The same as a persistent program: its ready line, then `answer` to every case line.
std::string answering_persistently(const std::string& answer) {
  return "sh -c 'echo \"{\\\"version\\\": 1, \\\"ready\\\": true}\"; while read -r line; do echo \"$0\"; done' '" +
         answer + "'";
}

Settings with_command(const std::string& command) {
  Settings s;
  s.command = command;
  return s;
}

// The issue's pair (3 storeys each, one contact per floor): a whole answer for it.
const char* const kAnswer =
    R"({"version":1,"status":"ok","message":"mine","floor_peak":[[0.01,0.02,0.03],[0.04,0.05,0.06]],)"
    R"("drift_peak":[[0.01,0.01,0.01],[0.04,0.01,0.01]],"floor_peak_time":[[0.5,0.6,null],[0.7,0.8,0.9]],)"
    R"("contacts":[{"impacts":2,"impact_velocity_max":0.3,"first_impact":0.25},{"impacts":0},)"
    R"({"left":0,"right":1,"floor":3,"impacts":1,"contact_phases":1,"impact_velocity_max":0.1,"first_impact":0.4}],)"
    R"("steps":123,"min_gap":-1e-9,"solve_seconds":0.5})";

TEST(ExternalBuildings, TheCaseDocumentCarriesTheModelNumberForNumber) {
  const BuildingModel model = assemble(test::issue_scene());
  Settings settings;
  settings.steps = 64;
  const programs::CaseDocument doc = programs::buildings_case_document(model, settings, model.t_min / 64);
  ASSERT_EQ(doc.error, "");
  ASSERT_EQ(doc.text.back(), '\n');
  EXPECT_EQ(doc.text.find('\n'), doc.text.size() - 1);  // one line: the persistent protocol's
  const Json j = Json::parse(doc.text);
  EXPECT_EQ(j["scene"], "buildings");
  EXPECT_EQ(j["conventions"]["gap"], "delta + u_right - u_left");
  ASSERT_EQ(j["buildings"].size(), 2u);
  for (std::size_t b = 0; b < 2; ++b) {
    const Json& building = j["buildings"][b];
    EXPECT_EQ(building["masses"].get<std::vector<double>>(), model.scene.buildings[b].masses);
    EXPECT_EQ(building["stiffnesses"].get<std::vector<double>>(), model.scene.buildings[b].stiffnesses);
    EXPECT_EQ(building["damping"]["rule"], "rayleigh");
    const int first = model.first[b];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(building["C"][static_cast<std::size_t>(r)][static_cast<std::size_t>(c)].get<double>(),
                  model.C(first + r, first + c));
    // The rule's coefficients give C back: a0 M + a1 K.
    const double a0 = building["damping"]["a0"], a1 = building["damping"]["a1"];
    EXPECT_NEAR(building["C"][1][1].get<double>(), a0 * model.m(first + 1) + a1 * model.K(first + 1, first + 1),
                1e-9 * std::abs(model.C(first + 1, first + 1)));
  }
  ASSERT_EQ(j["contacts"].size(), 3u);
  EXPECT_EQ(j["contacts"][2]["floor"], 3);
  EXPECT_EQ(j["contacts"][2]["gap"].get<double>(), 0.03);
  EXPECT_EQ(j["load"]["kind"], "pulse");
  EXPECT_EQ(j["load"]["amplitude"].get<double>(), 3.0);
  EXPECT_EQ(j["t_end"].get<double>(), model.t_end);
  EXPECT_EQ(j["step"].get<double>(), model.t_min / 64);
  EXPECT_EQ(j["steps_per_period"], 64);
  // A record's samples, signed, as the oscillators' document carries them.
  const BuildingModel recorded = assemble(test::issue_scene_under_a_record());
  const Json r = Json::parse(programs::buildings_case_document(recorded, Settings{}).text);
  EXPECT_EQ(r["load"]["kind"], "record");
  EXPECT_EQ(r["load"]["a"].size(), 61u);
  EXPECT_TRUE(r["step"].is_null());
}

TEST(ExternalBuildings, AnAnswerIsTheResultItSaysPerPointAndPersistent) {
  const BuildingModel model = assemble(test::issue_scene());
  for (const bool persistent : {false, true}) {
    Settings settings = with_command(persistent ? answering_persistently(kAnswer) : answering(kAnswer));
    if (persistent) settings.variant = "persistent";
    const BuildingsResult r = external::solve_buildings(model, settings);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_EQ(r.message, "mine");
    EXPECT_EQ(r.floor_peak, (std::vector<std::vector<double>>{{0.01, 0.02, 0.03}, {0.04, 0.05, 0.06}}));
    EXPECT_EQ(r.drift_peak[1][0], 0.04);
    EXPECT_EQ(r.floor_peak_time[0][1], 0.6);
    EXPECT_TRUE(std::isnan(r.floor_peak_time[0][2]));
    EXPECT_TRUE(std::isnan(r.drift_peak_time[1][2]));  // not given: NaN, shaped as the peaks
    ASSERT_EQ(r.contacts.size(), 3u);
    EXPECT_EQ(r.contacts[0].impacts, 2);
    EXPECT_EQ(r.contacts[0].impact_velocity_max, 0.3);
    EXPECT_EQ(r.contacts[1].impacts, 0);
    EXPECT_TRUE(std::isnan(r.contacts[1].first_impact));
    EXPECT_EQ(r.contacts[2].floor, 3);
    EXPECT_EQ(r.contacts[2].contact_phases, 1);
    EXPECT_EQ(r.events, 123);
    EXPECT_EQ(r.min_gap, -1e-9);
    EXPECT_EQ(r.t_end, model.t_end);
  }
}

TEST(ExternalBuildings, AMalformedAnswerIsRefusedInOneLineNamingItsField) {
  const BuildingModel model = assemble(test::issue_scene());
  const std::string peaks = R"("floor_peak":[[1,2,3],[1,2,3]],"drift_peak":[[1,2,3],[1,2,3]])";
  const std::string contacts = R"("contacts":[{},{},{}])";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"version":1,"status":"ok",)" + contacts + "}", "answer: floor_peak: status ok needs the peak |u| of every floor"},
      {R"({"version":1,"status":"ok","floor_peak":[[1,2,3]],)" + contacts + "}",
       "answer: floor_peak: must be an array of 2 arrays, one per building"},
      {R"({"version":1,"status":"ok","floor_peak":[[1,2,3],[1,2]],)" + contacts + "}",
       "answer: floor_peak[1]: must be an array of 3 numbers"},
      {R"({"version":1,"status":"ok","floor_peak":[[1,2,3],[1,-2,3]],)" + contacts + "}",
       "answer: floor_peak[1][1]: must be a peak |u| >= 0"},
      {R"({"version":1,"status":"ok","floor_peak":[[1,2,3],[1,"2",3]],)" + contacts + "}",
       "answer: floor_peak[1][1]: must be a number"},
      {R"({"version":1,"status":"ok","floor_peak":[[1,2,3],[1,2,3]],)" + contacts + "}",
       "answer: drift_peak: status ok needs the peak drift of every storey"},
      {R"({"version":1,"status":"ok",)" + peaks + "}", "answer: contacts: status ok needs one object per contact"},
      {R"({"version":1,"status":"ok",)" + peaks + R"(,"contacts":[{},{}]})", "answer: contacts: must be an array of 3 objects"},
      {R"({"version":1,"status":"ok",)" + peaks + R"(,"contacts":[{},{"floor":1},{}]})",
       "answer: contacts[1].floor: must be the case's, 2"},
      {R"({"version":1,"status":"ok",)" + peaks + R"(,"contacts":[{},{"impacts":1.5},{}]})",
       "answer: contacts[1].impacts: must be a whole number >= 0"},
      {R"({"version":1,"status":"ok",)" + peaks + R"(,"contacts":[{},{"first_impact":1e9},{}]})",
       "answer: contacts[1].first_impact: must be within the run"},
      {R"({"version":1,"status":"ok",)" + peaks + R"(,"contacts":[{},{"impact":1},{}]})",
       "answer: contacts[1].impact: unknown key"},
      {R"({"version":1,"status":"ok",)" + peaks + "," + contacts + R"(,"pi1":1})", "answer: pi1: unknown key"},
      {R"({"version":1,"status":"ok",)" + peaks + "," + contacts + R"(,"floor_peak_time":[[0.1,0.2,0.3],[0.1,0.2,-1]]})",
       "answer: floor_peak_time[1][2]: must be within the run"},
      {R"({"version":1,"status":"fine"})", "answer: status: must be one of ok"},
      {R"({"version":2,"status":"ok"})", "answer: version: must be 1"},
      {R"({"version":1,"status":"failed","status":"ok"})", "answer: stdout: key \"status\" given twice"},
      {"not json", "answer: stdout: not one JSON document"},
  };
  for (const auto& [answer, expected] : cases) {
    const BuildingsResult r = external::solve_buildings(model, with_command(answering(answer)));
    EXPECT_EQ(r.status, Status::failed) << answer;
    EXPECT_TRUE(r.message.starts_with(expected)) << answer << "\n  " << r.message;
    EXPECT_EQ(r.message.find('\n'), std::string::npos) << r.message;
    EXPECT_TRUE(r.floor_peak.empty()) << answer;
  }
  // A status other than ok: its peaks are dropped, its message and counts kept.
  const BuildingsResult late = external::solve_buildings(
      model, with_command(answering(R"({"version":1,"status":"time-limit","message":"slow",)" + peaks + "}")));
  EXPECT_EQ(late.status, Status::time_limit);
  EXPECT_EQ(late.message, "slow");
  EXPECT_TRUE(late.floor_peak.empty());
}

TEST(ExternalBuildings, AProgramGoingWrongIsAResultAsForTheOscillators) {
  const BuildingModel model = assemble(test::issue_scene());
  const BuildingsResult exits = external::solve_buildings(model, with_command("sh -c 'echo oops >&2; exit 3'"));
  EXPECT_EQ(exits.status, Status::failed);
  EXPECT_EQ(exits.message, "the program exited with code 3; stderr: oops");
  const BuildingsResult missing = external::solve_buildings(model, with_command("/no/such/program"));
  EXPECT_EQ(missing.status, Status::failed);
  EXPECT_TRUE(missing.message.starts_with("command: cannot start")) << missing.message;
  Settings slow = with_command("sleep 10");
  slow.time_limit = 0.2;
  const BuildingsResult late = external::solve_buildings(model, slow);
  EXPECT_EQ(late.status, Status::time_limit);
  // A step past the pulse period is refused before the program starts, as the time-steppers refuse it.
  Settings far = with_command(answering(kAnswer));
  far.wh = 1e6;
  EXPECT_EQ(external::solve_buildings(model, far).status, Status::failed);
}

TEST(ExternalBuildings, TheRegistrysExternalRowSolvesTheScene) {
  const SolverInfo* info = find_solver("external");
  ASSERT_NE(info, nullptr);
  ASSERT_NE(info->solve_buildings, nullptr);
  const auto& read = info->buildings_settings;
  for (const char* field : {"command", "steps", "wh", "step_cap", "time_limit"})
    EXPECT_NE(std::find(read.begin(), read.end(), field), read.end()) << field;
  EXPECT_EQ(std::find(read.begin(), read.end(), "theta"), read.end());
}

}  // namespace external_buildings_tests
}  // namespace pb
