// The `poundbench` command line, run as a separate process: outputs, exit codes, the
// one-line error of every bad input, and the partial files of the sweep commands (resuming).

#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "cases/text.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "studies/stress.hpp"
#include "sweep/sweep.hpp"
#include "tests/cli_fixture.hpp"
#include "kit/testing.hpp"

extern char** environ;

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace cli_tests {

constexpr const char* kPairCase =
    "--scene pair --pulse sine --directivity normal --pi2 1 --pi3 0.5 --eps 0.5 --pi5 0.5 --pi6 1";

TEST_F(Cli, RunJsonPrintsTheSolversPi1) {
  const Outcome o = run(std::string("run ") + kPairCase + " --json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(o.err, "");
  const nlohmann::json j = nlohmann::json::parse(o.out);

  const Case c = test::make_case(Scene::pair, PulseShape::sine, 1.0, 0.5, 0.5);  // kPairCase
  const Row row = run_point(c, 0, *find_solver("event-driven"), Settings{});
  // JSON carries doubles with round-trip precision and the solver is deterministic.
  EXPECT_EQ(j.at("pi1").get<double>(), row.result.pi1);
  EXPECT_EQ(j.at("pi1_no_contact").get<double>(), row.pi1_no_contact);
  EXPECT_EQ(j.at("impacts").get<long>(), row.result.impacts);
  EXPECT_EQ(j.at("status"), "ok");
  EXPECT_EQ(j.at("solver"), "event-driven");
  EXPECT_EQ(j.at("scene"), "pair");
  EXPECT_EQ(j.at("pi5").get<double>(), 0.5);
  EXPECT_FALSE(j.contains("pi7"));
  for (const char* key : {"contact_phases", "steps", "message", "min_gap", "t_max", "variant", "settings", "seconds"})
    EXPECT_TRUE(j.contains(key)) << key;
}

// Issue 32: status ok means only that a run finished. Newmark at its defaults (N = 64,
// K = 1e4) on the issue's wall case ends ok with its contacts a step long, which its verdict
// cannot vouch for: `run` says so under the status and on stderr, and `--json` carries the
// verdict (false, with its reason); the reference's run is resolved. (Before Newmark split its
// steps at contact changes, that run also made energy and ended far off, Pi1 8.1 against
// 1.80; now 1.799, the exact Kelvin-Voigt model's 1.806.)
TEST_F(Cli, RunSaysWhenAFinishedRunDidNotResolveWhatItSolved) {
  const std::string wall = "run --scene wall --pulse cosine --directivity normal --pi2 1 --pi3 0.5 --eps 0.5";
  const Outcome text = run(wall + " --solver compliant --integrator newmark");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("\nverdict  UNRESOLVED, do not trust this Pi1: a contact lasted"), std::string::npos)
      << text.out;
  EXPECT_NE(text.err.find("warning: the run did not resolve what it solved"), std::string::npos) << text.err;
  const nlohmann::json j = nlohmann::json::parse(run(wall + " --solver compliant --integrator newmark --json").out);
  EXPECT_EQ(j.at("status"), "ok");
  EXPECT_EQ(j.at("resolved"), false);
  EXPECT_NE(j.at("unresolved").get<std::string>().find("a contact lasted"), std::string::npos) << j.at("unresolved");
  const nlohmann::json ref = nlohmann::json::parse(run(wall + " --json").out);
  EXPECT_EQ(ref.at("resolved"), true);
  EXPECT_EQ(ref.at("unresolved"), "");
  EXPECT_NEAR(ref.at("pi1").get<double>(), 1.80, 0.01);
  const Outcome failed = run(wall + " --solver moreau-jean --step-cap 2 --json");
  EXPECT_TRUE(nlohmann::json::parse(failed.out).at("resolved").is_null());  // not ok: not judged
}

// Issue 48: a resolved run was no promise of accuracy. Moreau-Jean at N = 12 on the issue's
// wall case gives Pi1 1.572 against the reference's 0.810 (94 % off) and passed every criterion
// of the verdict; `run` now estimates its error from a companion solve at 2h, prints it and
// calls the run unresolved naming the estimate (--json: resolved false, error_estimate).
TEST_F(Cli, RunCallsACoarseRunNinetyFourPercentOffUnresolvedNamingItsErrorEstimate) {
  const std::string issue =
      "run --scene wall --pulse cosine --directivity reverse --pi2 1.0424 --pi3 0.259 --eps 0.9 --solver moreau-jean "
      "--steps 12";
  const Outcome text = run(issue);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("\nverdict  UNRESOLVED, do not trust this Pi1: error estimate "), std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("\nerror    estimate "), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("(companion solve at 2h, order 1)"), std::string::npos) << text.out;
  const nlohmann::json j = nlohmann::json::parse(run(issue + " --json").out);
  EXPECT_NEAR(j.at("pi1").get<double>(), 1.572, 0.001);
  EXPECT_EQ(j.at("resolved"), false);
  EXPECT_EQ(j.at("unresolved").get<std::string>().find("error estimate "), 0u) << j.at("unresolved");
  EXPECT_GT(j.at("error_estimate").get<double>(), 0.1);
  // A looser target does not rescue it; the reference has no fixed step and no estimate.
  EXPECT_EQ(nlohmann::json::parse(run(issue + " --json --target-error 0.2").out).at("resolved"), false);
  const nlohmann::json ref = nlohmann::json::parse(
      run("run --scene wall --pulse cosine --directivity reverse --pi2 1.0424 --pi3 0.259 --eps 0.9 --json").out);
  EXPECT_NEAR(ref.at("pi1").get<double>(), 0.810, 0.001);
  EXPECT_TRUE(ref.at("error_estimate").is_null());
  EXPECT_EQ(ref.at("resolved"), true);
}

// The estimate does not make every time-stepper unresolved: a fine step on a smooth case (no
// impact: the gap never closes) is resolved, its estimate far below the 1 % target.
TEST_F(Cli, AFineStepOnASmoothCaseIsResolvedWithASmallErrorEstimate) {
  const Outcome o = run(
      "run --scene wall --pulse sine --directivity normal --pi2 1 --pi3 5 --eps 0.5 --solver moreau-jean --steps 1000 "
      "--json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j.at("impacts"), 0);
  EXPECT_EQ(j.at("resolved"), true) << j.at("unresolved");
  EXPECT_LT(j.at("error_estimate").get<double>(), 1e-3);
}

// A sweep estimates only when asked (--estimate-error: a companion solve per point); without it
// the error_estimate column is empty and no fixed-step row says resolved true (not judged:
// what was not measured could have failed); so without --monitor. With both, every row is judged.
TEST_F(Cli, ASweepWithoutEstimateErrorHasAnEmptyColumnAndNoResolvedRow) {
  write("tiny.toml", kTinySet);
  for (const char* flags : {"", " --monitor"}) {
    const Outcome o = run(std::string("spectrum tiny.toml --solver moreau-jean --steps 64") + flags);
    ASSERT_EQ(o.exit_code, 0) << o.err;
    CsvTable t(o.out);
    ASSERT_EQ(t.rows.size(), 6u);
    for (std::size_t k = 0; k < t.rows.size(); ++k) {
      EXPECT_EQ(t.at(k, "error_estimate"), "") << flags;
      EXPECT_NE(t.at(k, "resolved"), "true") << flags;
    }
  }
  const Outcome unmonitored = run("spectrum tiny.toml --solver moreau-jean --steps 64 --estimate-error");
  CsvTable u(unmonitored.out);
  for (std::size_t k = 0; k < u.rows.size(); ++k) EXPECT_NE(u.at(k, "resolved"), "true");
  const Outcome both = run("spectrum tiny.toml --solver moreau-jean --steps 64 --monitor --estimate-error");
  ASSERT_EQ(both.exit_code, 0) << both.err;
  CsvTable b(both.out);
  for (std::size_t k = 0; k < b.rows.size(); ++k) {
    EXPECT_NE(b.at(k, "error_estimate"), "");
    EXPECT_NE(b.at(k, "resolved"), "");
    const std::string velocity = b.at(k, "error_estimate_velocity");  // empty: no impact at either step
    if (std::stod(b.at(k, "error_estimate")) > 0.01 || (!velocity.empty() && std::stod(velocity) > 0.01)) {
      EXPECT_EQ(b.at(k, "resolved"), "false");
    }
  }
  const Outcome unused = run("spectrum tiny.toml --solver moreau-jean --target-error 0.05");
  EXPECT_EQ(unused.exit_code, 2);
  EXPECT_NE(unused.err.find("--target-error: only used with --estimate-error"), std::string::npos) << unused.err;
  EXPECT_EQ(run("run --scene wall --pulse sine --directivity normal --pi2 1 --pi3 1 --eps 0.5 --target-error 0")
                .exit_code,
            2);
}

TEST_F(Cli, RunWritesTheHistoryWithThePapersBodyLabels) {
  const Outcome o = run(
      "run --scene row3 --pulse cosine --directivity normal --pi2 2 --pi3 0.5 --eps 0.5 --pi5 0.5 --pi6 2 "
      "--pi7 2 --pi8 0.5 --history h.csv --samples 50");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const std::string text = read_text(file("h.csv"));
  EXPECT_EQ(text.substr(0, text.find('\n')), "t,u1,u0,u2,v1,v0,v2,g1,g2,lambda1,lambda2");
  EXPECT_EQ(line_count(text), 51u);
  EXPECT_EQ(files(), (std::set<std::string>{"h.csv"}));
}

TEST_F(Cli, RunOfAChainReportsItsBodiesKickAndOneColumnPerBody) {
  const Outcome o = run(
      "run --scene chain --bodies 4 --kick 0.5 --pulse sine --directivity normal --pi2 1 --pi3 0.5 --eps 1 "
      "--pi5 0.5 --pi6 2 --json --history h.csv --samples 10");
  // The solvers' chain support is young: whatever the status, the output must describe the chain.
  ASSERT_TRUE(o.exit_code == 0 || o.exit_code == 1) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j.at("scene"), "chain");
  EXPECT_EQ(j.at("bodies"), 4);
  EXPECT_EQ(j.at("kick").get<double>(), 0.5);
  EXPECT_EQ(j.at("pi6").get<double>(), 2.0);
  EXPECT_FALSE(j.contains("pi7"));
  for (const char* key : {"energy_excess", "penetration", "isolated_impacts", "restitution_low", "restitution_high", "wh"})
    EXPECT_TRUE(j.contains(key)) << key;
  const std::string text = read_text(file("h.csv"));
  EXPECT_EQ(text.substr(0, text.find('\n')), "t,u0,u1,u2,u3,v0,v1,v2,v3,g1,g2,g3,lambda1,lambda2,lambda3");

  const Outcome pair = run(std::string("run ") + kPairCase + " --json");
  ASSERT_EQ(pair.exit_code, 0) << pair.err;
  const nlohmann::json p = nlohmann::json::parse(pair.out);
  EXPECT_FALSE(p.contains("bodies"));
  EXPECT_FALSE(p.contains("kick"));
}

TEST_F(Cli, RunWithWhStepsATimeStepperAtThatWmaxH) {
  const Outcome o = run(std::string("run ") + kPairCase + " --solver moreau-jean --wh 2 --json");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_NEAR(j.at("wh").get<double>(), 2.0, 1e-12);
  EXPECT_EQ(j.at("settings").at("wh"), 2.0) << j.at("settings");
  // The same run through the library: the JSON is its row.
  const Case c = test::make_case(Scene::pair, PulseShape::sine, 1.0, 0.5, 0.5);
  Settings st;
  st.wh = 2;
  const Row row = run_point(c, 0, *find_solver("moreau-jean"), st);
  EXPECT_EQ(j.at("steps").get<long>(), row.result.steps);
  EXPECT_EQ(j.at("pi1").get<double>(), row.result.pi1);
  EXPECT_EQ(j.at("isolated_impacts").get<long>(), row.result.isolated_impacts);
  EXPECT_TRUE(j.at("energy_excess").is_number());  // its one solve monitored (issue 36)
  EXPECT_TRUE(j.at("penetration").is_number());
  const Outcome monitored = run(std::string("run ") + kPairCase + " --solver moreau-jean --wh 2 --json --monitor");
  ASSERT_EQ(monitored.exit_code, 0) << monitored.err;
  const nlohmann::json m = nlohmann::json::parse(monitored.out);
  EXPECT_TRUE(m.at("energy_excess").is_number());  // the monitored pass measured it
  EXPECT_EQ(m.at("pi1").get<double>(), j.at("pi1").get<double>());  // and changed nothing

  const Outcome both = run(std::string("run ") + kPairCase + " --solver moreau-jean --wh 2 --steps 64");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("--wh"), std::string::npos) << both.err;
}

TEST_F(Cli, RunFromACaseFileNeedsAPointWhenItHasSeveral) {
  write("tiny.toml", kTinySet);
  const Outcome chosen = run("run --case-file tiny.toml --point 4 --json");
  ASSERT_EQ(chosen.exit_code, 0) << chosen.err;
  const nlohmann::json j = nlohmann::json::parse(chosen.out);
  EXPECT_EQ(j.at("point"), 4);
  EXPECT_EQ(j.at("pulse"), "cosine");  // points 3..5 are the cosine spectrum

  const Outcome missing = run("run --case-file tiny.toml");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("--point"), std::string::npos) << missing.err;
}

struct BadInput {
  std::string args;
  std::string names;  // the flag or file the error line must name
};

// Three settings of moreau-jean: N = 64, and w_max h = 2 and 6 under a time limit (6: a step
// just within the step bound, at most the pulse period, on the pulse-dominated tiny cases).
constexpr const char* kTinyList = R"(name = "tiny"
[[run]]
solver = "moreau-jean"
steps = 64
[[run]]
solver = "moreau-jean"
wh = [2, 6]
time_limit = 5
)";

// The studies' inputs in place: kTinySet as tiny.toml, kTinyList as list.toml.
class CliStudy : public Cli {
 protected:
  void SetUp() override {
    Cli::SetUp();
    write("tiny.toml", kTinySet);
    write("list.toml", kTinyList);
  }
};

// Each bad input exits 2 with one line on stderr naming the culprit, and creates no file:
// every command below asks for an output file that must not appear.
TEST_F(CliStudy, EveryBadInputExitsTwoWithOneLineAndNoOutputFile) {
  write("bad-list.toml", "[[run]]\nsolver = \"moreau-jean\"\nwh = 0\n");
  write("syntax.toml", "name = \"broken\"\n[[family]]\nscene = \"pair\"\npi2 = [1, \n");
  write("semantic.toml", "name = \"bad\"\n[[family]]\nname = \"f\"\nscene = \"pair\"\npulse = \"sine\"\n"
                         "directivity = \"normal\"\neps = 0.5\npi2 = 1\npi3 = 0.5\npi5 = -1\npi6 = 1\n");
  const std::string wall = "--pulse sine --directivity normal --pi2 1 --pi3 0.5 --eps 0.5 --history h.csv";
  const std::string pair = "run --scene pair --pulse sine --directivity normal --pi2 1 --pi3 0.5 --eps 0.5 ";
  // The wall run with the value of `flag` replaced.
  const auto wall_with = [&wall](const std::string& flag, const std::string& value) {
    std::string args = "run --scene wall " + wall;
    const std::size_t at = args.find(flag + " ") + flag.size() + 1;
    return args.replace(at, args.find(' ', at) - at, value);
  };
  const std::vector<BadInput> cases = {
      {"run --scene tower " + wall, "--scene"},
      {pair + "--pi6 1 --history h.csv", "--pi5"},
      {pair + "--pi5 1 --pi6 1 --pi7 1 --history h.csv", "--pi7"},
      {wall_with("--eps", "1.5"), "--eps"},
      {wall_with("--pi2", "nan"), "--pi2"},
      {wall_with("--pi3", "-0.5"), "--pi3"},
      {wall_with("--pi2", "abc"), "--pi2"},
      {"run --scene wall " + wall + " --solver no-such-solver", "--solver"},
      {"run --scene wall " + wall + " --tol-scale 0", "--tol-scale"},
      {"run --scene wall " + wall + " --bogus-flag", "--bogus-flag"},
      {"run --case-file syntax.toml --history h.csv", "syntax.toml"},
      {"run --case-file tiny.toml --point 6 --history h.csv", "--point"},
      {"spectrum syntax.toml --out out.csv", "syntax.toml"},
      {"spectrum semantic.toml --out out.csv", "semantic.toml"},
      {"spectrum missing.toml --out out.csv", "missing.toml"},
      {"spectrum tiny.toml --out out.csv --solver no-such-solver", "--solver"},
      {"spectrum tiny.toml --out no-such-dir/out.csv", "--out"},
      {"spectrum tiny.toml --out out.csv --threads 0", "--threads"},
      {"run --scene chain --pulse sine --directivity normal --pi2 1 --pi3 0.5 --eps 1 --pi5 1 --pi6 1 --history h.csv",
       "--bodies"},
      {pair + "--pi5 1 --pi6 1 --bodies 3 --history h.csv", "--bodies"},
      {pair + "--pi5 1 --pi6 1 --kick 1 --history h.csv", "--kick"},
      {pair + "--pi5 1 --pi6 1 --solver moreau-jean --wh 0.5 --steps 8 --history h.csv", "--wh"},
      {pair + "--pi5 1 --pi6 1 --solver moreau-jean --wh -1 --history h.csv", "--wh"},
      {"stress tiny.toml --settings missing.toml --out out.csv", "missing.toml"},
      {"stress tiny.toml --settings bad-list.toml --out out.csv", "bad-list.toml:3: run[0].wh"},
      {"stress tiny.toml --settings list.toml --out no-such-dir/out.csv", "--out"},
      {"stress tiny.toml --settings list.toml --out out.csv --points no-such-dir/p.csv", "--points"},
      {"stress semantic.toml --settings list.toml --out out.csv", "semantic.toml"},
      {"stress tiny.toml --out out.csv", "--settings"},
      {"stress tiny.toml --settings list.toml --out out.csv --repetitions 0", "--repetitions"},
      {"workprecision tiny.toml --settings list.toml --out out.csv --repetitions 1001", "--repetitions"},
      {"spectrum tiny.toml --out out.csv --repetitions 0", "--repetitions"},
      {"spectrum tiny.toml --out out.csv --repetitions 2.5", "--repetitions"},
      {"workprecision tiny.toml --settings list.toml --out out.csv --check --max-error -1", "--max-error"},
      {"workprecision tiny.toml --settings list.toml --out out.csv --check --max-error inf", "--max-error"},
      {"workprecision tiny.toml --settings list.toml --out out.csv --max-error 0.1", "--max-error"},
  };
  const std::set<std::string> inputs = files();
  for (const BadInput& bad : cases) {
    const Outcome o = run(bad.args);
    EXPECT_EQ(o.exit_code, 2) << bad.args;
    EXPECT_EQ(line_count(o.err), 1u) << bad.args << "\n" << o.err;
    EXPECT_NE(o.err.find(bad.names), std::string::npos) << bad.args << "\n" << o.err;
    EXPECT_EQ(o.out, "") << bad.args;
    EXPECT_EQ(files(), inputs) << bad.args;
  }
}

// --- issue 15: inputs inside a documented domain, or refused ------------------------------

// The command lines of issue 15's fuzzer and their neighbours.
class CliInput : public Cli {
 protected:
  // Exit 2, one line on stderr holding every one of `names`, nothing on stdout, no new file.
  void expect_refused(const std::string& args, std::initializer_list<std::string> names) const {
    SCOPED_TRACE(args.substr(0, 200));
    const std::set<std::string> before = files();
    const Outcome o = run(args);
    const std::string err = o.err.substr(0, 500);
    EXPECT_EQ(o.exit_code, 2) << err;
    EXPECT_EQ(line_count(o.err), 1u) << err;
    for (const std::string& name : names) EXPECT_NE(o.err.find(name), std::string::npos) << name << "\n" << err;
    EXPECT_EQ(o.out, "");
    EXPECT_EQ(files(), before);
  }
};

// `run` of kPairCase with one flag set to `value` (replaced, or added when kPairCase lacks it).
std::string run_pair_with(const std::string& flag, const std::string& value) {
  std::istringstream words(kPairCase);
  std::string args = "run", word;
  bool replaced = false;
  while (words >> word) {
    args += " " + word;
    if (word == flag) {
      words >> word;
      args += " " + value;
      replaced = true;
    }
  }
  return replaced ? args : args + " " + flag + " " + value;
}

TEST_F(CliInput, RunRefusesTheFuzzersInputsOutsideTheDomainNamingTheBound) {
  expect_refused(run_pair_with("--w-p", "1e100"), {"--w-p: ", "[1e-6, 1e6]"});
  expect_refused(run_pair_with("--a-p", "1e200"), {"--a-p: ", "[1e-12, 1e12]"});
  expect_refused(run_pair_with("--n-free", "1e308"), {"--n-free: ", "<= 1000"});
  expect_refused(run_pair_with("--pi2", "1e-100"), {"--pi2: ", "contrast (max/min) of 1e100, more than 1e4"});
  expect_refused(run_pair_with("--pi5", "1e308"), {"--pi5: ", "more than 1e4"});
  expect_refused(run_pair_with("--pi3", "1e7"), {"--pi3: ", "<= 1e6"});
  for (const char* value : {"1e-300", "1e308"}) {
    expect_refused(run_pair_with("--pi2", value), {"--pi2: ", "more than 1e4"});
    expect_refused(run_pair_with("--pi5", value), {"--pi5: ", "more than 1e4"});
    expect_refused(run_pair_with("--pi6", value), {"--pi6: ", "more than 1e6"});
    expect_refused(run_pair_with("--a-p", value), {"--a-p: ", "[1e-12, 1e12]"});
    expect_refused(run_pair_with("--w-p", value), {"--w-p: ", "[1e-6, 1e6]"});
  }
  // Each value alone is inside, but the run would last (1 + 1000 / 1e-3) shortest periods.
  expect_refused(run_pair_with("--pi5", "1000") + " --n-free 1000",
                 {"--n-free: ", "shortest periods", "more than 1e6"});
}

TEST_F(CliInput, RunAtTheCornersOfThePulseScalesGivesTheSamePi1) {
  const Outcome unit = run("run --scene pair --pulse cosine --directivity normal --pi2 0.8 --pi3 0.5 --eps 0.5 "
                           "--pi5 0.5 --pi6 1 --json");
  ASSERT_EQ(unit.exit_code, 0) << unit.err;
  const double pi1 = nlohmann::json::parse(unit.out).at("pi1").get<double>();
  for (const char* scales : {"--a-p 1e-12 --w-p 1e6", "--a-p 1e12 --w-p 1e-6"}) {
    const Outcome o = run("run --scene pair --pulse cosine --directivity normal --pi2 0.8 --pi3 0.5 --eps 0.5 "
                          "--pi5 0.5 --pi6 1 --json " + std::string(scales));
    ASSERT_EQ(o.exit_code, 0) << scales << ": " << o.err;
    EXPECT_NEAR(nlohmann::json::parse(o.out).at("pi1").get<double>(), pi1, 1e-9 * pi1) << scales;
  }
}

TEST_F(CliInput, EveryOptionRefusesAnEmptyValue) {
  write("tiny.toml", kTinySet);
  const std::string pair = std::string("run ") + kPairCase + " ";
  for (const char* flag : {"--pi3", "--eps", "--pi5", "--xi", "--n-free", "--a-p", "--w-p", "--steps", "--wh",
                           "--theta", "--step-cap", "--time-limit", "--tol-scale", "--solver", "--variant"})
    expect_refused(pair + flag + " ''", {std::string(flag) + ": ", "empty value"});
  expect_refused("compare rows.csv --baseline base.csv --tolerance ''", {"--tolerance: ", "empty value"});
  expect_refused("spectrum tiny.toml --out ''", {"--out: ", "empty value"});
  expect_refused("spectrum tiny.toml --threads '' --out out.csv", {"--threads: ", "empty value"});
}

TEST_F(CliInput, NegativeOrNanLimitsAreRefusedWhateverTheSolver) {
  const std::string pair = std::string("run ") + kPairCase + " ";
  for (const char* solver : {"event-driven", "moreau-jean"}) {
    const std::string with_solver = pair + "--solver " + solver + " ";
    expect_refused(with_solver + "--step-cap -1", {"--step-cap: ", ">= 0"});
    expect_refused(with_solver + "--time-limit -1", {"--time-limit: ", ">= 0"});
    expect_refused(with_solver + "--time-limit nan", {"--time-limit: ", "finite"});
    expect_refused(with_solver + "--time-limit inf", {"--time-limit: ", "finite"});
  }
}

TEST_F(CliInput, HistorySamplesAreCappedBeforeTheRun) {
  const std::string pair = std::string("run ") + kPairCase + " --history h.csv ";
  expect_refused(pair + "--samples 100000000", {"--samples: ", "<= 1000000"});
  expect_refused(pair + "--samples 1000001", {"--samples: ", "<= 1000000"});
  // A chain of 1000 bodies has 3999 values a sample.
  expect_refused("run --scene chain --bodies 1000 --pulse sine --directivity normal --pi2 1 --pi3 0.5 --eps 1 "
                 "--pi5 1 --pi6 1 --history h.csv --samples 10000", {"--samples: at most 5001 for this scene"});
  const Outcome most = run(pair + "--samples 1000000");
  ASSERT_EQ(most.exit_code, 0) << most.err;
  EXPECT_EQ(line_count(read_text(file("h.csv"))), 1'000'001u);
}

TEST_F(CliInput, AHistoryThatCannotBeCreatedIsRefusedBeforeTheSolve) {
  // As root, access() says yes to everything; /proc takes no new files from anyone.
  expect_refused(std::string("run ") + kPairCase + " --history /proc/poundbench-history.csv",
                 {"--history: /proc/poundbench-history.csv: cannot create: ", "No such file or directory"});
  EXPECT_FALSE(fs::exists("/proc/poundbench-history.csv.tmp"));
  // The probe leaves no temporary behind where it can create one.
  ASSERT_EQ(run(std::string("run ") + kPairCase + " --history h.csv --samples 10").exit_code, 0);
  EXPECT_EQ(files(), (std::set<std::string>{"h.csv"}));
}

TEST_F(CliInput, AHugeKeyOrValueIsEchoedClippedOnOneShortLine) {
  const std::string key(10'000'000, 'k');
  write("set.toml", std::string(kTinySet) + key + " = 1\n");
  write("list.toml", std::string("[[run]]\nsolver = \"moreau-jean\"\n") + key + " = 1\n");
  write("tiny.toml", kTinySet);
  expect_refused("spectrum set.toml --out out.csv",
                 {"set.toml:12: family[0]." + std::string(kMaxEchoed, 'k') + "...: ", "unknown key"});
  // The settings reader (sweep/) echoes the key whole: main clips every part of the line.
  expect_refused("stress tiny.toml --settings list.toml --out out.csv", {"list.toml:3: run[0].", "...: unknown key"});
  for (const char* command :
       {"spectrum set.toml --out out.csv", "stress tiny.toml --settings list.toml --out out.csv"})
    EXPECT_LT(run(command).err.size(), 1100u) << command;
  const std::string value(100'000, 'v');
  const Outcome scene = run("run --scene " + value + " --pulse sine --directivity normal --pi2 1 --pi3 0.5 --eps 1");
  EXPECT_EQ(scene.exit_code, 2);
  EXPECT_LT(scene.err.size(), 200u);
  EXPECT_NE(scene.err.find("--scene: unknown value '" + std::string(kMaxEchoed, 'v') + "...'"), std::string::npos)
      << scene.err;
}

TEST_F(Cli, SpectrumWritesOneRowPerPointInOrderAndNoLeftovers) {
  write("tiny.toml", kTinySet);
  const Outcome o = run("spectrum tiny.toml --out out.csv --threads 2");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(files(), (std::set<std::string>{"tiny.toml", "out.csv"}));
  std::ifstream in(file("out.csv"));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, csv_header());
  int point = 0;
  while (std::getline(in, line)) {
    EXPECT_EQ(line.rfind("pair," + std::to_string(point) + ",pair,", 0), 0u) << line;
    ++point;
  }
  EXPECT_EQ(point, 6);
}

// Renaming a temporary onto a device or a pipe would replace it with a regular file (as
// root, even /dev/null): such an output is written in place. (A sweep refuses one, since
// it keeps a partial file beside its output: tests/sweep_files_test.cpp.)
TEST_F(Cli, AnOutputThatIsAPipeStaysAPipe) {
  write("tiny.toml", kTinySet);
  ASSERT_EQ(::mkfifo(file("pipe").c_str(), 0644), 0);
  const std::string reader = "cat '" + file("pipe").string() + "' > '" + file("got.csv").string() + "' &";
  ASSERT_EQ(std::system(reader.c_str()), 0);
  const Outcome o = run("baseline tiny.toml --out pipe");
  // Should poundbench never have opened the pipe, this releases the waiting reader.
  if (const int fd = ::open(file("pipe").c_str(), O_WRONLY | O_NONBLOCK); fd >= 0) ::close(fd);
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(fs::is_fifo(file("pipe")));
  // The reader ends when the writer closes the pipe.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (read_text(file("got.csv")).find("\npair,5,") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const std::string got = read_text(file("got.csv"));
  const std::size_t header = got.find(csv_header());  // after the baseline's comment lines
  ASSERT_NE(header, std::string::npos) << got;
  EXPECT_EQ(CsvTable(got.substr(header)).rows.size(), 6u);
  EXPECT_FALSE(fs::exists(file("pipe.tmp")));
}

TEST_F(Cli, SpectrumToStdoutLeavesNoPartialFile) {
  write("tiny.toml", kTinySet);
  const Outcome o = run("spectrum tiny.toml");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(line_count(o.out), 7u);
  EXPECT_EQ(files(), (std::set<std::string>{"tiny.toml"}));
}

// A sweep of 200000 points (kTinySet's two spectra at 100000 points each: far more than
// finish in the test's few seconds): interrupt it once rows are arriving, then check what
// it leaves.
TEST_F(Cli, InterruptedSpectrumKeepsThePartialFileAndWritesNoFinalFile) {
  std::string big_set = kTinySet;
  const std::string tiny_grid = "points = 3";
  write("big.toml", big_set.replace(big_set.find(tiny_grid), tiny_grid.size(), "points = 100000"));
  const std::string big = file("big.toml").string(), out = file("out.csv").string();
  const std::string log = file("stderr.txt").string();
  const pid_t pid = spawn_poundbench({"spectrum", big, "--out", out, "--threads", "2"}, dir_, "/dev/null", log);

  // Wait (at most 20 s) for the header and a few rows in the partial file, then interrupt.
  const fs::path partial = file("out.csv.partial");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < deadline &&
         (!fs::exists(partial) || line_count(read_text(partial)) < 4))
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid, SIGINT);

  int status = 0;
  pid_t waited = 0;
  const auto exit_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while ((waited = ::waitpid(pid, &status, WNOHANG)) == 0 && std::chrono::steady_clock::now() < exit_deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (waited == 0) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    FAIL() << "poundbench did not stop within 20 s of SIGINT";
  }

  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out + ".tmp"));
  const std::string rows = read_text(partial);
  EXPECT_GE(line_count(rows), 4u);
  EXPECT_LT(line_count(rows), 200001u);
  EXPECT_EQ(rows.back(), '\n');  // no row cut in half
  const std::string err = read_text(log);
  EXPECT_EQ(line_count(err), 1u) << err;
  EXPECT_NE(err.find("out.csv.partial"), std::string::npos) << err;
}

// The rows a partial file already holds are kept as they are (their `seconds`, set to
// 12345 here, shows it) and only the missing points run: the output equals an
// uninterrupted run's, and the partial file is gone.
TEST_F(Cli, SpectrumResumesFromItsPartialFileRunningOnlyTheMissingPoints) {
  write("tiny.toml", kTinySet);
  ASSERT_EQ(run("spectrum tiny.toml --out full.csv").exit_code, 0);
  CsvTable full(read_text(file("full.csv")));
  ASSERT_EQ(full.rows.size(), 6u);
  const std::string cut_short = CsvTable::line(full.rows[3]).substr(0, 30);  // a write a crash cut
  full.at(4, "seconds") = "12345";
  full.at(1, "seconds") = "12345";
  write("out.csv.partial", CsvTable::line(full.columns) + "\n" + CsvTable::line(full.rows[4]) + "\n" +
                               CsvTable::line(full.rows[1]) + "\n" + cut_short);

  const Outcome o = run("spectrum tiny.toml --out out.csv");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(files(), (std::set<std::string>{"tiny.toml", "full.csv", "out.csv"}));
  CsvTable out(read_text(file("out.csv")));
  EXPECT_EQ(out.without(kTimingColumns).rows, full.without(kTimingColumns).rows);
  for (std::size_t point = 0; point < 6; ++point)
    EXPECT_EQ(out.at(point, "seconds") == "12345", point == 1 || point == 4) << point;
}

TEST_F(Cli, SpectrumRefusesThePartialFileOfAnotherSweep) {
  write("tiny.toml", kTinySet);
  ASSERT_EQ(run("spectrum tiny.toml --solver moreau-jean --out mj.csv").exit_code, 0);
  const CsvTable mj(read_text(file("mj.csv")));
  const std::string partial = CsvTable::line(mj.columns) + "\n" + CsvTable::line(mj.rows[2]) + "\n";
  write("out.csv.partial", partial);

  const Outcome o = run("spectrum tiny.toml --out out.csv");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(line_count(o.err), 1u) << o.err;
  EXPECT_NE(o.err.find("out.csv.partial:2: point 2: solver is \"moreau-jean\" there"), std::string::npos) << o.err;
  EXPECT_EQ(files(), (std::set<std::string>{"tiny.toml", "mj.csv", "out.csv.partial"}));
  EXPECT_EQ(read_text(file("out.csv.partial")), partial);
}

// A study's partial file has a run column (0: the truth); its rows are kept and the
// summary and every run's row come out as an uninterrupted study's.
TEST_F(CliStudy, AStudyResumesFromItsPartialFileToTheSameSummaryAndRuns) {
  ASSERT_EQ(run("workprecision tiny.toml --settings list.toml --out sum.csv --points runs.csv").exit_code, 0);
  CsvTable runs(read_text(file("runs.csv")));
  ASSERT_EQ(runs.rows.size(), 24u);  // 6 points, the truth and 3 settings
  std::string partial = "run," + CsvTable::line(runs.columns) + "\n";
  for (std::size_t row : {7u, 2u, 20u}) {
    runs.at(row, "seconds") = "12345";
    partial += std::to_string(row / 6) + "," + CsvTable::line(runs.rows[row]) + "\n";
  }
  write("sum2.csv.partial", partial);

  const Outcome o = run("workprecision tiny.toml --settings list.toml --out sum2.csv --points runs2.csv");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_FALSE(fs::exists(file("sum2.csv.partial")));
  const CsvTable resumed(read_text(file("runs2.csv")));
  EXPECT_EQ(resumed.without(kTimingColumns).rows, runs.without(kTimingColumns).rows);
  for (std::size_t row = 0; row < 24; ++row)
    EXPECT_EQ(resumed.rows[row][runs.column("seconds")] == "12345", row == 2 || row == 7 || row == 20) << row;
  const std::initializer_list<std::string_view> cpu = {"cpu_median_s", "cpu_mean_s", "cpu_median_low_s",
                                                        "cpu_median_high_s", "repetitions"};
  EXPECT_EQ(CsvTable(read_text(file("sum2.csv"))).without(cpu).rows,
            CsvTable(read_text(file("sum.csv"))).without(cpu).rows);
}

TEST_F(CliStudy, StressWritesASummaryPerFamilyAndSettingAndEveryRunWithItsPi1Error) {
  const Outcome o = run("stress tiny.toml --settings list.toml --out sum.csv --points runs.csv --threads 2");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(o.out, "");
  EXPECT_EQ(files(), (std::set<std::string>{"tiny.toml", "list.toml", "sum.csv", "runs.csv"}));

  std::ifstream summary(file("sum.csv"));
  std::string line;
  std::getline(summary, line);
  EXPECT_EQ(line, stability_csv_header());
  std::vector<std::string> solvers;
  while (std::getline(summary, line)) {
    EXPECT_EQ(line.rfind("pair,", 0), 0u) << line;  // the one family
    solvers.push_back(line.substr(5, line.find(',', 5) - 5));
    EXPECT_NE(line.find(",6,6,"), std::string::npos) << line;  // 6 runs, all finished
  }
  // The truth first, then the list's three settings.
  EXPECT_EQ(solvers, (std::vector<std::string>{"event-driven", "moreau-jean", "moreau-jean", "moreau-jean"}));

  std::ifstream points(file("runs.csv"));
  std::getline(points, line);
  EXPECT_EQ(line, stress_points_header());
  std::size_t rows = 0, compared = 0;
  while (std::getline(points, line)) {
    ++rows;
    const std::string error = line.substr(line.rfind(',') + 1);
    if (rows <= 6) {
      EXPECT_EQ(error, "") << line;  // the truth is not compared with itself
    } else {
      ++compared;
      EXPECT_NE(error, "") << line;
      EXPECT_LT(std::strtod(error.c_str(), nullptr), rows <= 12 ? 0.02 : 10.0) << line;  // N = 64 first
    }
  }
  EXPECT_EQ(rows, 6u * 4u);
  EXPECT_EQ(compared, 18u);

  const Outcome to_stdout = run("stress tiny.toml --settings list.toml");
  ASSERT_EQ(to_stdout.exit_code, 0) << to_stdout.err;
  EXPECT_EQ(line_count(to_stdout.out), 5u);
}

// --check: the outputs are written whatever the verdict; the exit code says whether a row
// failed, and stderr names each one and then counts them. Moreau-Jean at w_max h = 6
// passes every stability check and fails accuracy; at N = 64 it passes them all.
TEST_F(CliStudy, CheckExitsOneWhenARowFailsAfterWritingTheOutputs) {
  Outcome o = run("stress tiny.toml --settings list.toml --out sum.csv --check");
  EXPECT_EQ(o.exit_code, 1) << o.err;
  EXPECT_TRUE(fs::exists(file("sum.csv")));
  const std::string wh6 = R"(poundbench: stress --check: pair moreau-jean {"wh":6,"theta":0.5,"gamma":0.5}: )";
  EXPECT_NE(o.err.find(wh6 + "failed accuracy\n"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("event-driven"), std::string::npos) << o.err;  // the truth passes
  const std::string last = o.err.substr(o.err.rfind('\n', o.err.size() - 2) + 1);
  EXPECT_EQ(last.rfind("poundbench: stress --check: ", 0), 0u) << o.err;
  EXPECT_NE(last.find(" of 4 rows failed\n"), std::string::npos) << last;
  // The wrote line, one line per failed row, the count.
  EXPECT_EQ(line_count(o.err), 2u + std::stoul(last.substr(28))) << o.err;
  EXPECT_EQ(o.err.rfind("poundbench: wrote 4 rows to sum.csv in ", 0), 0u) << o.err;

  write("n64.toml", "name = \"n64\"\n[[run]]\nsolver = \"moreau-jean\"\nsteps = 64\n");
  o = run("stress tiny.toml --settings n64.toml --out sum64.csv --check");
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_NE(o.err.find("\npoundbench: stress --check: 0 of 2 rows failed\n"), std::string::npos) << o.err;
  EXPECT_EQ(line_count(o.err), 2u) << o.err;
  EXPECT_EQ(run("stress tiny.toml --settings list.toml --out plain.csv").exit_code, 0);  // no --check: 0

  // workprecision: every run finished, but those at w_max h = 2 and 6 (fewer than 4 steps a
  // shortest period) did not resolve what they solved (kit/verdict.hpp), which fails their
  // rows; an err_median above --max-error fails its row too.
  const std::string wp6 = R"(poundbench: workprecision --check: pair moreau-jean {"wh":6,"theta":0.5,"gamma":0.5}: )";
  o = run("workprecision tiny.toml --settings list.toml --out wp.csv --check");
  EXPECT_EQ(o.exit_code, 1) << o.err;
  EXPECT_NE(o.err.find(wp6 + "6 of 6 runs finished without resolving what they solved"), std::string::npos) << o.err;
  o = run("workprecision tiny.toml --settings list.toml --out wp.csv --check --max-error 0.05");
  EXPECT_EQ(o.exit_code, 1) << o.err;
  EXPECT_NE(o.err.find("(kit/verdict.hpp); err_median "), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("steps"), std::string::npos) << "N = 64 is within 5 %: " << o.err;
  EXPECT_TRUE(fs::exists(file("wp.csv")));
}

// --repetitions: each row says how many timed solves it had (at most R; a point stops once
// its solves have spent 10 ms), and its CPU time is their median, within their range.
TEST_F(CliStudy, RepetitionsAreRecordedInEveryRow) {
  ASSERT_EQ(run("spectrum tiny.toml --solver moreau-jean --out r3.csv --repetitions 3 --monitor").exit_code, 0);
  ASSERT_EQ(run("spectrum tiny.toml --solver moreau-jean --out r1.csv --monitor").exit_code, 0);
  ASSERT_EQ(run("spectrum tiny.toml --solver moreau-jean --out once.csv").exit_code, 0);
  const CsvTable r3(read_text(file("r3.csv"))), r1(read_text(file("r1.csv"))), once(read_text(file("once.csv")));
  ASSERT_EQ(r3.rows.size(), 6u);
  for (std::size_t i = 0; i < r3.rows.size(); ++i) {
    const auto number = [&](const CsvTable& t, std::string_view column) {
      return std::strtod(t.rows[i][t.column(column)].c_str(), nullptr);
    };
    // µs solves: all three, unless the first ones spent the point's budget (a sanitizer build,
    // a loaded machine): then those that ran spent it.
    const double reps = number(r3, "repetitions");
    EXPECT_TRUE(reps == 3 || (reps >= 1 && reps < 3 && reps * number(r3, "cpu_seconds_high") >= kRepetitionBudget))
        << reps << " repetitions, the slowest " << number(r3, "cpu_seconds_high") << " s";
    EXPECT_EQ(r1.rows[i][r1.column("repetitions")], "1") << "spectrum's default";
    EXPECT_LE(number(r3, "cpu_seconds_low"), number(r3, "cpu_seconds"));
    EXPECT_LE(number(r3, "cpu_seconds"), number(r3, "cpu_seconds_high"));
    EXPECT_EQ(number(r1, "cpu_seconds_low"), number(r1, "cpu_seconds"));
    // Timed without the monitor, its measurements from a pass of their own all the same.
    EXPECT_NE(r3.rows[i][r3.column("energy_excess")], "");
    // Without --monitor each point is solved once: no monitor columns, the same answer.
    EXPECT_EQ(once.rows[i][once.column("energy_excess")], "");
    EXPECT_EQ(once.rows[i][once.column("pi1")], r1.rows[i][r1.column("pi1")]);
  }
  EXPECT_EQ(r3.without(kTimingColumns).rows, r1.without(kTimingColumns).rows);
}

// A baseline stored, checked unchanged (exit 0), checked after one stored Pi1 was nudged
// (exit 1, the setting named), and stored again on purpose (exit 0, then clean again).
TEST_F(CliStudy, BaselineCheckCatchesAChangedPi1AndUpdateStoresItAgain) {
  const Outcome made = run("baseline tiny.toml --settings list.toml --out base.csv");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  EXPECT_EQ(made.out, "");
  EXPECT_EQ(made.err.rfind("poundbench: wrote 24 rows to base.csv in ", 0), 0u) << made.err;
  const std::string stored = read_text(file("base.csv"));
  EXPECT_EQ(stored.rfind("# poundbench baseline\n# cases: tiny.toml\n# settings: list.toml\n# commit: ", 0), 0u);

  Outcome checked = run("baseline --check base.csv");
  ASSERT_EQ(checked.exit_code, 0) << checked.out << checked.err;
  EXPECT_EQ(checked.out.find("FAIL"), std::string::npos);

  // The first Moreau-Jean row's Pi1, one part in 1e9 larger: beyond its 1e-12.
  std::string nudged = stored;
  const std::size_t row = nudged.find(",moreau-jean,");
  const std::size_t pi1 = nudged.find(",ok,", row) + 4;
  const std::size_t end = nudged.find(',', pi1);
  const double value = std::strtod(nudged.substr(pi1, end - pi1).c_str(), nullptr);
  std::ostringstream text;
  text.precision(17);
  text << value * (1.0 + 1e-9);
  nudged.replace(pi1, end - pi1, text.str());
  write("base.csv", nudged);
  checked = run("baseline --check base.csv");
  EXPECT_EQ(checked.exit_code, 1) << checked.out << checked.err;
  EXPECT_NE(checked.out.find("FAIL"), std::string::npos) << checked.out;

  const Outcome updated = run("baseline --update base.csv");
  ASSERT_EQ(updated.exit_code, 0) << updated.err;
  EXPECT_NE(updated.out.find("stored again (24 rows); it had changed"), std::string::npos) << updated.out;
  EXPECT_EQ(run("baseline --check base.csv").exit_code, 0);
}

TEST_F(Cli, CompareChecksAnotherSolversRowsAgainstTheStoredReference) {
  write("tiny.toml", kTinySet);
  ASSERT_EQ(run("baseline tiny.toml --out base.csv").exit_code, 0);
  ASSERT_EQ(run("spectrum tiny.toml --solver moreau-jean --steps 64 --out mine.csv").exit_code, 0);
  // Measured 0.4 % at N = 64 on these six points.
  Outcome o = run("compare mine.csv --baseline base.csv --tolerance 0.02");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  EXPECT_NE(o.out.find("pass"), std::string::npos) << o.out;
  o = run("compare mine.csv --baseline base.csv --tolerance 1e-6");
  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;
  EXPECT_NE(o.out.find("FAIL"), std::string::npos) << o.out;

  o = run("compare mine.csv --baseline base.csv");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err, "poundbench: --tolerance: required (or --same-setting)\n");
  write("bad.csv", "family,point\n");
  o = run("compare bad.csv --baseline base.csv --tolerance 1");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err, "poundbench: bad.csv:1: scene: missing column\n");
  o = run("baseline --check mine.csv");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err.rfind("poundbench: mine.csv:1: header: not a poundbench baseline", 0), 0u) << o.err;
}

// A minimal file: the case columns of the row key and pi1, nothing else (another
// program's output), here the tiny set's sine rows of the baseline with Pi1 moved by 1e-3.
TEST_F(Cli, CompareReadsRowsWithOnlyTheMinimalColumns) {
  write("tiny.toml", kTinySet);
  ASSERT_EQ(run("baseline tiny.toml --out base.csv").exit_code, 0);
  const std::string base = read_text(file("base.csv"));
  CsvTable stored(base.substr(base.find("family,")));
  std::vector<std::pair<std::string, double>> sine;  // pi2, pi1
  for (std::size_t row = 0; row < stored.rows.size(); ++row)
    if (stored.at(row, "pulse") == "sine")
      sine.emplace_back(stored.at(row, "pi2"), std::strtod(stored.at(row, "pi1").c_str(), nullptr) * (1.0 + 1e-3));
  ASSERT_EQ(sine.size(), 3u);
  // The file, with or without the pi6 column.
  const auto minimal = [&](bool pi6) {
    std::ostringstream text;
    text.precision(17);
    text << "scene,pulse,directivity,pi2,pi3,eps,pi5," << (pi6 ? "pi6," : "") << "pi1\n";
    for (const auto& [pi2, pi1] : sine) text << "pair,sine,normal," << pi2 << ",0.5,0.5,0.75," << (pi6 ? "1," : "") << pi1 << "\n";
    return text.str();
  };
  write("minimal.csv", minimal(true));

  Outcome o = run("compare minimal.csv --baseline base.csv --tolerance 2e-3");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  EXPECT_NE(o.out.find("max rel |dPi1|"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("       3       0         0        0        1.00e-03      2e-03  pass"), std::string::npos)
      << o.out;
  o = run("compare minimal.csv --baseline base.csv --tolerance 5e-4");
  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;
  EXPECT_EQ(o.err, "");

  // A column the rows' scene needs, and pi1, cannot be left out; those it does not can.
  write("no-pi6.csv", minimal(false));
  o = run("compare no-pi6.csv --baseline base.csv --tolerance 1");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err, "poundbench: no-pi6.csv:2: pi6: missing column (scene pair uses it)\n");
  write("wall.csv", "scene,pulse,directivity,pi2,pi3,eps,status,pi1\nwall,sine,normal,1,0.5,0.5,failed,\n");
  o = run("compare wall.csv --baseline base.csv --tolerance 1");
  EXPECT_EQ(o.exit_code, 1) << o.err;  // read, and no stored row of that case
  EXPECT_NE(o.out.find("FAIL"), std::string::npos) << o.out;
  write("no-pi1.csv", "scene,pulse,directivity,pi2,pi3,eps\nwall,sine,normal,1,0.5,0.5\n");
  o = run("compare no-pi1.csv --baseline base.csv --tolerance 1");
  EXPECT_EQ(o.err, "poundbench: no-pi1.csv:1: pi1: missing column\n");
}

// The first line a shell command prints ("" if none).
std::string first_line(const std::string& command) {
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return "";
  char buffer[256] = {};
  const bool got = std::fgets(buffer, sizeof buffer, pipe) != nullptr;
  ::pclose(pipe);
  std::string line = got ? buffer : "";
  if (!line.empty() && line.back() == '\n') line.pop_back();
  return line;
}

TEST_F(Cli, VersionSaysTheProjectVersionAndTheCommitItWasBuiltFrom) {
  const Outcome o = run("--version");
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(o.out.rfind("poundbench 0.", 0), 0u) << o.out;  // CMakeLists.txt: project(VERSION 0.1)
  ASSERT_NE(o.out.find(", commit "), std::string::npos) << o.out;
  const std::string commit = o.out.substr(o.out.find(", commit ") + 9);
  const std::string head = first_line("git -C '" POUNDBENCH_SOURCE_DIR "' rev-parse --short HEAD 2>/dev/null");
  if (head.empty())
    EXPECT_EQ(commit, "unknown\n");  // not a git checkout
  else
    EXPECT_EQ(commit.rfind(head, 0), 0u) << commit << " vs " << head;
}

TEST_F(Cli, AWordThatIsNoSubcommandIsNamedAndTheSubcommandsListed) {
  const std::string list =
      "the subcommands are: run, spectrum, workprecision, stress, separation, baseline, compare, solvers, adapter, report "
      "(`poundbench help` says what each does)\n";
  Outcome o = run("bogus --out x.csv");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err, "poundbench: unknown subcommand 'bogus'; " + list);
  o = run("");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err, "poundbench: no subcommand; " + list);
  o = run("help spectrumm");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err, "poundbench: unknown subcommand 'spectrumm' (did you mean spectrum?); " + list);
  o = run("help");
  EXPECT_EQ(o.exit_code, 0);
  EXPECT_EQ(o.out, run("--help").out);
  EXPECT_NE(o.out.find("Usage: poundbench"), std::string::npos) << o.out;
  for (const char* name : {"run", "spectrum", "workprecision", "stress", "baseline", "compare", "solvers"})
    EXPECT_NE(o.out.find(std::string("  ") + name + " "), std::string::npos) << name;
  o = run("help stress");
  EXPECT_EQ(o.exit_code, 0);
  EXPECT_NE(o.out.find("Usage: poundbench stress"), std::string::npos) << o.out;
}

// `solvers` lists every variant the registry has, the default first, with what it is and
// the settings it uses; `run --variant` takes each one it lists.
TEST_F(Cli, SolversListsEveryVariantAndRunAcceptsEachOne) {
  const Outcome text = run("solvers");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const Outcome json = run("solvers --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json listed = nlohmann::json::parse(json.out).at("solvers");
  ASSERT_EQ(listed.size(), solvers().size());
  for (std::size_t k = 0; k < solvers().size(); ++k) {
    const SolverInfo& solver = solvers()[k];
    SCOPED_TRACE(std::string(solver.name));
    EXPECT_EQ(listed[k].at("name"), solver.name);
    ASSERT_NE(solver.variants, nullptr);
    const std::vector<VariantInfo> variants = solver.variants();
    ASSERT_FALSE(variants.empty());
    ASSERT_EQ(listed[k].at("variants").size(), variants.size());
    // The first is what the empty name runs.
    Settings first;
    first.variant = variants.front().name;
    EXPECT_EQ(solver.describe(first), solver.describe(Settings{}));
    std::set<std::string> summaries;
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const std::string name(variants[v].name);
      const nlohmann::json& entry = listed[k].at("variants")[v];
      EXPECT_EQ(entry.at("name"), name);
      EXPECT_EQ(entry.at("default"), v == 0);
      EXPECT_TRUE(summaries.insert(variants[v].summary).second) << "two variants alike: " << variants[v].summary;
      EXPECT_NE(text.out.find("      " + (name.empty() ? "(default)" : name) + (v == 0 && !name.empty() ? " (default)" : "") +
                              "  "),
                std::string::npos)
          << name;
      if (name.empty()) continue;  // no option takes an empty value
      // The external solver needs its program: poundbench itself.
      const std::string command =
          solver.name != "external" ? ""
          : name == "persistent"    ? " --command '" POUNDBENCH_EXE " adapter --persistent --solver moreau-jean'"
                                    : " --command '" POUNDBENCH_EXE " adapter --solver moreau-jean'";
      const Outcome o = run(std::string("run ") + kPairCase + " --solver " + std::string(solver.name) + " --variant " +
                            name + command + " --json");
      EXPECT_NE(o.exit_code, 2) << name << ": " << o.err;
      if (!o.out.empty()) {
        EXPECT_EQ(nlohmann::json::parse(o.out).at("variant"), name);
      }
    }
  }
  // What each uses, as the settings column of its rows shows it.
  EXPECT_NE(text.out.find("    settings: --steps --wh --h-s --theta --gamma --steps-per-sample\n"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("    settings: --tol-scale --contact\n"), std::string::npos) << text.out;
  EXPECT_EQ(settings_used(*find_solver("moreau-jean"), "end-samples"),
            (std::vector<std::string_view>{"steps", "wh", "h_s", "theta", "gamma", "steps_per_sample"}));
  // A setting used only under another value of a name (compliant's step under Newmark) is listed
  // on its own line, and the run it names accepts it.
  if (find_solver("compliant")) {
    EXPECT_NE(text.out.find("    with --integrator newmark: --steps --wh --h-s --steps-per-sample\n"), std::string::npos)
        << text.out;
    const Outcome newmark = run(std::string("run ") + kPairCase + " --solver compliant --integrator newmark --steps 64");
    EXPECT_EQ(newmark.exit_code, 0) << newmark.err;
  }
  EXPECT_EQ(settings_used(reference_solver(), ""), (std::vector<std::string_view>{"tol_scale", "contact"}));
}

// Every sweep command ends with a line per file it wrote, whatever stderr is (here a file).
TEST_F(CliStudy, EverySweepCommandSaysWhatItWroteInItsLastLines) {
  const auto wrote = [](const std::string& err, std::size_t rows, const std::string& to) {
    const std::string head = "poundbench: wrote " + std::to_string(rows) + " rows to " + to + " in ";
    const std::size_t at = err.find(head);
    if (at == std::string::npos) return false;
    const std::string seconds = err.substr(at + head.size(), err.find('\n', at) - at - head.size());
    return seconds.size() >= 5 && seconds.ends_with(" s") && seconds[seconds.size() - 4] == '.';
  };
  Outcome o = run("spectrum tiny.toml --out out.csv");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(wrote(o.err, 6, "out.csv")) << o.err;
  EXPECT_EQ(line_count(o.err), 1u) << o.err;
  o = run("workprecision tiny.toml --settings list.toml --out sum.csv --points runs.csv");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(wrote(o.err, 24, "runs.csv")) << o.err;  // the truth and 3 settings on 6 points
  EXPECT_TRUE(wrote(o.err, line_count(read_text(file("sum.csv"))) - 1, "sum.csv")) << o.err;
  EXPECT_EQ(line_count(o.err), 2u) << o.err;
  o = run("stress tiny.toml --settings list.toml");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(wrote(o.err, 4, "stdout")) << o.err;
  o = run("baseline tiny.toml --out base.csv");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(wrote(o.err, 6, "base.csv")) << o.err;
}

TEST_F(Cli, HelpExitsZeroOnEverySubcommand) {
  for (const char* command : {"--help", "run --help", "spectrum --help", "workprecision --help", "stress --help",
                              "baseline --help", "compare --help", "solvers --help"}) {
    const Outcome o = run(command);
    EXPECT_EQ(o.exit_code, 0) << command;
    EXPECT_NE(o.out.find("Usage"), std::string::npos) << command;
  }
  const Outcome solvers = run("solvers");
  EXPECT_EQ(solvers.exit_code, 0);
  EXPECT_NE(solvers.out.find("event-driven"), std::string::npos);
}

}  // namespace cli_tests
}  // namespace pb
