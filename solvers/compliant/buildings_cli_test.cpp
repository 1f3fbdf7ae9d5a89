// `poundbench run --case-file FILE --point N --solver compliant` on the buildings scene
// (solvers/compliant/buildings.hpp): the same JSON as the reference's, its answer near the
// reference's at the default stiffness, Newmark's step in it, and what it does not read refused.

#ifdef POUNDBENCH_HAVE_SUNDIALS

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/cli_fixture.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace buildings_compliant_cli_tests {

const std::string kBuildingsSet = kSource + "/cases/sets/buildings.toml";

TEST_F(Cli, CompliantSolvesABuildingsPointInTheReferencesJsonShape) {
  const Outcome o = run("run --case-file '" + kBuildingsSet + "' --point 0 --solver compliant --json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["solver"], "compliant");
  EXPECT_EQ(j["status"], "ok");
  EXPECT_FALSE(j.contains("step_s"));  // CVODE chooses its steps
  EXPECT_GT(j["events"].get<long>(), 0);
  EXPECT_TRUE(j["energy_error"].is_null());  // not measured
  const Outcome exact = run("run --case-file '" + kBuildingsSet + "' --point 0 --json");
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  const nlohmann::json ref = nlohmann::json::parse(exact.out);
  // At the default K = 1e4 the elements' model error is about 1e-3 of a peak (buildings_test.cpp).
  for (const char* key : {"floor_peak_m", "drift_peak_m"}) {
    ASSERT_EQ(j[key].size(), 2u) << key;
    for (std::size_t b = 0; b < 2; ++b) {
      ASSERT_EQ(j[key][b].size(), ref[key][b].size()) << key;
      for (std::size_t i = 0; i < j[key][b].size(); ++i) {
        const double x = j[key][b][i], y = ref[key][b][i];
        EXPECT_NEAR(x / y, 1.0, 1e-2) << key << " building " << b << " floor " << i + 1;
      }
    }
  }
  ASSERT_EQ(j["contacts"].size(), 3u);
  long impacts = 0;
  for (const auto& k : j["contacts"]) {
    EXPECT_EQ(k["contact_phases"], 0);  // an element has no persistent phase of its own
    impacts += k["impacts"].get<long>();
    EXPECT_EQ(k["first_impact_s"].is_null(), k["impacts"] == 0);
  }
  EXPECT_GT(impacts, 0);

  const std::string point = "run --case-file '" + kBuildingsSet + "' --point 0 --solver compliant";
  const Outcome nm = run(point + " --integrator newmark --steps 128 --json");
  ASSERT_EQ(nm.exit_code, 0) << nm.err;
  const nlohmann::json jn = nlohmann::json::parse(nm.out);
  EXPECT_EQ(jn["status"], "ok");
  // h = t_min / N, t_min the shortest of T_p and the buildings' periods.
  const double h = jn["step_s"].get<double>();
  EXPECT_GT(h, 0.0);
  EXPECT_LE(h * 128.0 * ref["w_p"].get<double>(), 2.0 * std::numbers::pi * (1.0 + 1e-12));

  const Outcome unread = run(point + " --integrator newmark --steps-per-sample 2");
  EXPECT_EQ(unread.exit_code, 2);
  EXPECT_NE(unread.err.find("--steps-per-sample: not used by compliant on the buildings scene (it reads --stiffness"),
            std::string::npos)
      << unread.err;
  EXPECT_EQ(std::count(unread.err.begin(), unread.err.end(), '\n'), 1) << unread.err;
}

}  // namespace buildings_compliant_cli_tests
}  // namespace pb

#endif  // POUNDBENCH_HAVE_SUNDIALS
