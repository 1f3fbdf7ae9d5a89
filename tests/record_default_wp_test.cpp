// A record has no parameter a user must invent (issue 34): with neither w_p nor tp its Pi
// terms are measured against its mean frequency 2 pi / T_m (Rathje et al. 1998), on the
// command line and in case sets; `run` says which w_p it used and where it came from; and a
// record with no mean period asks for tp, naming the file.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "cases/case_set.hpp"
#include "cases/record.hpp"
#include "tests/cli_fixture.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace record_default_wp_tests {

const std::string kPair = " --scene pair --directivity normal --pi2 1 --pi3 0.5 --eps 0.5 --pi5 0.5 --pi6 1";

TEST(RecordDefaultWp, EveryCaseOfTheRealSuiteSetTakesItsRecordsMeanFrequency) {
  const CaseSet set = load_case_set(kSource + "/cases/sets/records-real.toml");
  ASSERT_FALSE(set.cases.empty());
  for (const Case& c : set.cases) {
    ASSERT_TRUE(c.samples) << c.record;
    // T_m of a real record lies well inside the band (0.05 to 4 s): a NaN or a wild value
    // would be a reader or FFT fault, not a property of the suite.
    ASSERT_GT(c.samples->t_m, 0.05) << c.record;
    ASSERT_LT(c.samples->t_m, 4.0) << c.record;
    EXPECT_EQ(c.w_p, 2.0 * std::numbers::pi / c.samples->t_m) << c.record;  // the same expression: exact
    EXPECT_EQ(c.a_p, c.samples->peak) << c.record;
  }
}

class RecordDefaultWpCli : public Cli {};

TEST_F(RecordDefaultWpCli, RunWithNoTpUsesTheMeanPeriodAndSaysSo) {
  const std::string record = kSource + "/cases/records/real/TCU054-N.AT2";
  const Outcome json = run("run --pulse record --record '" + record + "'" + kPair + " --solver event-driven --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  const double t_m = j.at("record_t_m").get<double>();
  EXPECT_EQ(j.at("w_p_source"), "mean period");
  EXPECT_DOUBLE_EQ(j.at("w_p").get<double>(), 2.0 * std::numbers::pi / t_m);  // printed at 17 digits
  // Given as tp = T_m, the same case to the bit: the default is that tp and nothing else.
  char tp[40];
  std::snprintf(tp, sizeof tp, "%.17g", t_m);
  const Outcome given = run("run --pulse record --record '" + record + "' --tp " + tp + kPair +
                            " --solver event-driven --json");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  const auto g = nlohmann::json::parse(given.out);
  EXPECT_EQ(g.at("pi1"), j.at("pi1"));
  EXPECT_EQ(g.at("w_p_source"), "mean period");  // the w_p used is the mean frequency, given or not
  const Outcome other = run("run --pulse record --record '" + record + "' --tp 1" + kPair + " --solver event-driven --json");
  ASSERT_EQ(other.exit_code, 0) << other.err;
  EXPECT_EQ(nlohmann::json::parse(other.out).at("w_p_source"), "given");
  const Outcome text = run("run --pulse record --record '" + record + "'" + kPair + " --solver event-driven");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("mean period T_m "), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("2 pi / T_m"), std::string::npos) << text.out;
}

TEST_F(RecordDefaultWpCli, ARecordWithNoMeanPeriodAsksForTpNamingTheFile) {
  // Three samples 0.01 s apart: its padded FFT's first frequency is 25 Hz, above the band.
  write("fast.csv", "t,a\n0,1\n0.01,2\n0.02,1\n");
  const Outcome o = run("run --pulse record --record fast.csv" + kPair + " --solver event-driven");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.err.find("--tp: required by --record fast.csv: it has no mean period"), std::string::npos) << o.err;
  EXPECT_EQ(line_count(o.err), 1u) << o.err;
  write("x.toml", "name = \"x\"\n[[family]]\nname = \"f\"\nscene = \"wall\"\ndirectivity = \"normal\"\n"
                  "pulse = \"record\"\nrecord = \"fast.csv\"\npi2 = 1\npi3 = 0.5\neps = 0.5\n");
  const Outcome set = run("spectrum x.toml --solver event-driven");
  EXPECT_EQ(set.exit_code, 2);
  EXPECT_NE(set.err.find("x.toml:7: family[0].record: fast.csv: it has no mean period"), std::string::npos) << set.err;
}

}  // namespace record_default_wp_tests
}  // namespace pb
