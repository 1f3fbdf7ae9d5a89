// Two solvers through the command line (tests/cli_fixture.hpp): the Kelvin-Voigt reference's
// peak contact force on README's physical example, and the external solver's flags, rows and
// adapter. Here rather than in the solvers' folders: a command-line test is the command's.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "kit/testing.hpp"
#include "tests/cli_fixture.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace solver_cli_tests {

using test::sci;

// The largest contact force is located as the deepest penetration is (issue 48): where the
// force's rate turns from rising to falling inside a stretch. README's physical example (El
// Centro, two 1e6 kg buildings 1 cm apart) at k = 1e10 N/m: an independent integration that
// locates the peak gives 2,933,362 N, where the force read at the stretches' ends gave
// 2,933,356 N (2.1e-6 low).
TEST_F(Cli, TheKelvinVoigtReferenceLocatesThePeakContactForce) {
  const Outcome o = run("run --scene pair --pulse record --record " + std::string(POUNDBENCH_SOURCE_DIR) +
                        "/cases/records/real/B-ELC000.AT2 --t0 0.5 --t1 1 --m0 1e6 --m1 1e6 --gap 0.01 --eps 0.6"
                        " --solver event-driven --contact kelvin-voigt --k-contact 1e10 --json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const auto j = nlohmann::json::parse(o.out);
  ASSERT_EQ(j["status"], "ok") << j["message"];
  const double force = j["contact_force_max"].get<double>();
  RecordProperty("contact_force_max_N", sci(force));
  EXPECT_NEAR(force, 2933362.0, 5e-7 * 2933362.0);
}

TEST_F(Cli, ExternalWithoutACommandIsABadInput) {
  const Outcome o = run("run --scene wall --pulse sine --directivity normal --pi2 1 --pi3 1 --eps 0.5 --solver external");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err, "poundbench: --command: required by solver external (the program and its arguments, e.g. "
                   "\"python3 adapter.py\")\n");
}

TEST_F(Cli, ExternalRowsNameTheCommandAndAFailingProgramIsARowNotAStop) {
  write("set.toml", kTinySet);
  const Outcome o = run("spectrum set.toml --threads 2 --solver external --command \"sh -c 'exit 4'\"");
  EXPECT_EQ(o.exit_code, 0) << o.err;
  CsvTable table(o.out);
  ASSERT_EQ(table.rows.size(), 6u);
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    EXPECT_EQ(table.at(i, "status"), "failed");
    EXPECT_EQ(table.at(i, "message"), "the program exited with code 4");
    EXPECT_EQ(table.at(i, "settings"), R"({"command":"sh -c 'exit 4'"})");
  }
}

TEST_F(Cli, AdapterRefusesABadCaseDocumentAsABadInput) {
  write("case.json", R"({"protocol":"poundbench-external","version":1,"bodies":[]})");
  const Outcome o = run("adapter --solver moreau-jean < case.json");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err, "poundbench: stdin: bodies: must be a non-empty array\n");
  const Outcome steps = run("adapter --solver moreau-jean --steps 8 < case.json");
  EXPECT_EQ(steps.exit_code, 2);
  EXPECT_EQ(steps.err, "poundbench: --steps: the case document gives it (run the sweep with it instead)\n");
}

}  // namespace solver_cli_tests
}  // namespace pb
