// Moreau-Jean on a buildings point through the command line (tests/cli_fixture.hpp): `run
// --case-file F --point N --solver moreau-jean` gives the reference's keys and shapes, its step
// too, near the reference's answer, and refuses a setting its buildings solve does not read.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/cli_fixture.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace buildings_mj_cli_tests {

const std::string kBuildingsSet = "'" + kSource + "/cases/sets/buildings.toml'";

TEST_F(Cli, MoreauJeanSolvesABuildingsPointWithTheReferencesKeys) {
  const Outcome o = run("run --case-file " + kBuildingsSet + " --point 0 --solver moreau-jean --steps 64 --json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["solver"], "moreau-jean");
  EXPECT_EQ(j["status"], "ok") << j["message"];
  EXPECT_GT(j["step_s"].get<double>(), 0.0);
  EXPECT_GT(j["events"].get<long>(), 0);  // its steps
  EXPECT_TRUE(j["energy_error"].is_null());  // not measured
  const Outcome exact = run("run --case-file " + kBuildingsSet + " --point 0 --json");
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  const nlohmann::json e = nlohmann::json::parse(exact.out);
  // The 3 + 6 storey pair: every floor's and storey's peak within the first-order error of
  // N = 64 (measured 1.3 % at most), and the contacts as the reference lists them.
  for (const char* key : {"floor_peak_m", "drift_peak_m"}) {
    ASSERT_EQ(j[key].size(), 2u) << key;
    for (std::size_t b = 0; b < 2; ++b) {
      ASSERT_EQ(j[key][b].size(), e[key][b].size()) << key;
      for (std::size_t i = 0; i < j[key][b].size(); ++i)
        EXPECT_NEAR(j[key][b][i].get<double>() / e[key][b][i].get<double>(), 1.0, 0.03) << key << " " << b << " " << i;
    }
  }
  ASSERT_EQ(j["contacts"].size(), e["contacts"].size());
  long impacts = 0;
  for (std::size_t c = 0; c < j["contacts"].size(); ++c) {
    const nlohmann::json& k = j["contacts"][c];
    EXPECT_EQ(k["floor"], e["contacts"][c]["floor"]);
    for (const char* key : {"impacts", "impact_velocity_max_m_s", "first_impact_s"}) EXPECT_TRUE(k.contains(key)) << key;
    impacts += k["impacts"].get<long>();
  }
  EXPECT_GT(impacts, 0);

  const Outcome summary = run("run --case-file " + kBuildingsSet + " --point 0 --solver moreau-jean");
  ASSERT_EQ(summary.exit_code, 0) << summary.err;
  for (const char* text : {"solver   moreau-jean, step ", "steps    ", "status   ok"})
    EXPECT_NE(summary.out.find(text), std::string::npos) << text << "\n" << summary.out;
}

TEST_F(Cli, MoreauJeanOnBuildingsRefusesWhatItDoesNotRead) {
  const Outcome o = run("run --case-file " + kBuildingsSet + " --point 0 --solver moreau-jean --history h.csv");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  const Outcome pulse = run("run --case-file " + kBuildingsSet + " --point 0 --solver moreau-jean --steps-per-sample 4 --json");
  EXPECT_EQ(pulse.exit_code, 1) << pulse.err;  // run, and failed (the point's load is a pulse): 1, as any run not ok
  const nlohmann::json j = nlohmann::json::parse(pulse.out);
  EXPECT_EQ(j["status"], "failed");
  EXPECT_NE(j["message"].get<std::string>().find("steps_per_sample: the step rule `record`"), std::string::npos);
}

}  // namespace buildings_mj_cli_tests
}  // namespace pb
