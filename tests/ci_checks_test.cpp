// The checks a CI relies on, run as a CI runs them (the poundbench binary, its exit code and
// its lines): compare's matching of cases within a tolerance and its naming of the nearest
// stored case, sweeps that say they failed, workprecision's gate on the 95th percentile,
// the commit a baseline names, JUnit reports, and a mistyped flag's "did you mean".

#include <cstdio>
#include <regex>
#include <string>

#include "cli_fixture.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace ci_checks_tests {

// kTinySet with a middle Pi2 (sqrt(0.3 * 3)) of more digits than 6: a row written to 6
// significant digits is not the stored double.
std::string irrational_set() {
  std::string set = kTinySet;
  const std::string grid = "from = 0.5, to = 2";
  return set.replace(set.find(grid), grid.size(), "from = 0.3, to = 3");
}

// A baseline's rows (after its comment lines) as another program writes them: the case
// columns and Pi1 only, every number to 6 significant digits (%g); `nudge_pi2` multiplies
// the Pi2 of the row at that index.
std::string six_digit_rows(const std::string& baseline, std::size_t nudged = SIZE_MAX, double nudge_pi2 = 1.0) {
  CsvTable stored(baseline.substr(baseline.find("family,")));
  std::string text = "scene,pulse,directivity,pi2,pi3,eps,pi5,pi6,pi1\n";
  for (std::size_t i = 0; i < stored.rows.size(); ++i) {
    const auto g = [&](std::string_view column, double factor = 1.0) {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%g", std::strtod(stored.at(i, column).c_str(), nullptr) * factor);
      return std::string(buffer);
    };
    text += stored.at(i, "scene") + "," + stored.at(i, "pulse") + "," + stored.at(i, "directivity") + "," +
            g("pi2", i == nudged ? nudge_pi2 : 1.0) + "," + g("pi3") + "," + g("eps") + "," + g("pi5") + "," +
            g("pi6") + "," + g("pi1") + "\n";
  }
  return text;
}

// The issue's complaint: rows written to 6 digits were "unmatched", and compare still
// passed. They match within 1e-5 (a 6-digit number is within 5e-6 of its double), their
// Pi1 within 5e-6 too; a row 1e-3 away in Pi2 matches nothing, fails, and is named with
// the stored case nearest to it, unless --allow-unmatched.
TEST_F(Cli, CompareMatchesSixDigitRowsAndFailsOnAnUnmatchedRowNamingTheNearestCase) {
  write("set.toml", irrational_set());
  ASSERT_EQ(run("baseline set.toml --out base.csv").exit_code, 0);
  const std::string base = read_text(file("base.csv"));
  write("mine.csv", six_digit_rows(base));
  Outcome o = run("compare mine.csv --baseline base.csv --tolerance 1e-5");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  EXPECT_NE(o.out.find("       6       0         0        0"), std::string::npos) << o.out;
  EXPECT_EQ(o.out.find("unmatched:"), std::string::npos) << o.out;

  write("moved.csv", six_digit_rows(base, 1, 1.001));
  o = run("compare moved.csv --baseline base.csv --tolerance 1e-5");
  EXPECT_EQ(o.exit_code, 1) << o.out << o.err;
  EXPECT_NE(o.out.find("       5       0         1        0"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("FAIL"), std::string::npos) << o.out;
  // The row's Pi2 is 1.001 sqrt(0.9); the stored one, point 1, is sqrt(0.9) = 0.948683...
  EXPECT_NE(o.out.find("unmatched: - -: point 1 (pair sine normal pi2=0.94963"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("the nearest stored case is family pair point 1: pi2=0.9486832980505"), std::string::npos)
      << o.out;
  EXPECT_NE(o.out.find("(1.0e-03 apart)"), std::string::npos) << o.out;

  o = run("compare moved.csv --baseline base.csv --tolerance 1e-5 --allow-unmatched");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  EXPECT_NE(o.out.find("unmatched: - -: point 1"), std::string::npos) << o.out;  // still named
}

// docs/cli.md's example row, a Fig. 4 point written to 5 digits, finds its stored case.
TEST_F(Cli, TheDocumentedCompareExampleMatchesThePaperReference) {
  write("example.csv", "scene,pulse,directivity,pi2,pi3,eps,pi5,pi6,pi1\npair,sine,normal,0.5,0.5,0.5,0.75,1,5.0698\n");
  const Outcome o = run("compare example.csv --baseline '" POUNDBENCH_SOURCE_DIR
                        "/tests/baselines/paper-reference.csv' --tolerance 1e-4");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  EXPECT_NE(o.out.find("       1       0         0        0"), std::string::npos) << o.out;
}

// The issue's sweep: every point failed (here: a program that exits 1) and it said "wrote
// 6 rows" alone, exit 0. Its closing line counts them; --check exits 1, names the family
// and the points; --junit writes them for a CI system.
TEST_F(Cli, ASweepWhosePointsFailedSaysSoAndCheckExitsOne) {
  write("tiny.toml", kTinySet);
  Outcome o = run("spectrum tiny.toml --solver external --command false --out out.csv");
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_NE(o.err.find(" s; 6 points did not finish ok (the status and message columns say why; --check makes this "
                       "exit 1)\n"),
            std::string::npos)
      << o.err;

  o = run("spectrum tiny.toml --solver external --command false --out out.csv --check --junit junit.xml");
  EXPECT_EQ(o.exit_code, 1) << o.err;
  EXPECT_NE(o.err.find("poundbench: spectrum --check: family pair: 6 of 6 points did not finish ok (point 0 failed, "
                       "point 1 failed"),
            std::string::npos)
      << o.err;
  EXPECT_NE(o.err.find("the first: the program exited with code 1\n"), std::string::npos) << o.err;
  EXPECT_TRUE(o.err.ends_with("poundbench: spectrum --check: 1 of 1 families failed\n")) << o.err;
  const std::string xml = read_text(file("junit.xml"));
  EXPECT_NE(xml.find("<testsuites name=\"poundbench spectrum\" tests=\"1\" failures=\"1\">"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<testcase classname=\"spectrum\" name=\"family pair\">\n      <failure message=\"6 of 6 points"),
            std::string::npos)
      << xml;

  o = run("spectrum tiny.toml --solver moreau-jean --out ok.csv --check");  // nothing failed: 0
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(o.err.ends_with("poundbench: spectrum --check: 0 of 1 families failed\n")) << o.err;
  o = run("spectrum tiny.toml --out j.csv --junit j.xml");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err, "poundbench: --junit: needs --check (it writes --check's verdicts)\n");
  EXPECT_FALSE(fs::exists(file("j.csv")));
}

// Moreau-Jean at w_max h = 6, just inside the step bound (w_p h <= 2 pi), errs 0.96 at its
// 95th percentile (0.72 median): it fails --max-error-p95 (and is unresolved: fewer than 4 steps
// a shortest period), and the line names its worst points; N = 64 (95th
// percentile 0.4 % here) passes.
TEST_F(Cli, WorkprecisionGatesTheNinetyFifthPercentileAndNamesTheFailingPoints) {
  write("tiny.toml", kTinySet);
  write("list.toml", "[[run]]\nsolver = \"moreau-jean\"\nsteps = 64\n[[run]]\nsolver = \"moreau-jean\"\nwh = 6\n");
  Outcome o = run("workprecision tiny.toml --settings list.toml --out wp.csv --check --max-error-p95 0.05 "
                  "--junit junit.xml");
  EXPECT_EQ(o.exit_code, 1) << o.err;
  const std::regex line(R"(poundbench: workprecision --check: pair moreau-jean \{"wh":6,"theta":0.5,"gamma":0.5\}: )"
                        R"(6 of 6 runs finished without resolving what they solved \(kit/verdict.hpp\); )"
                        R"(err_p95 [0-9.e-]+ above 0.05; above 0.05: point \d \([0-9.e-]+\))");
  EXPECT_TRUE(std::regex_search(o.err, line)) << o.err;
  EXPECT_EQ(o.err.find("steps"), std::string::npos) << o.err;
  EXPECT_TRUE(o.err.ends_with("poundbench: workprecision --check: 1 of 2 rows failed\n")) << o.err;
  const std::string xml = read_text(file("junit.xml"));
  EXPECT_NE(xml.find("tests=\"2\" failures=\"1\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("name=\"pair moreau-jean {&quot;steps&quot;:64,&quot;theta&quot;:0.5,&quot;gamma&quot;:0.5}\"/>"),
            std::string::npos)
      << xml;

  o = run("workprecision tiny.toml --settings list.toml --out wp.csv --max-error-p95 0.05");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err, "poundbench: --max-error-p95: needs --check\n");
}

// The commit a baseline names is the binary's that made its rows (what --version says),
// even where the file sits outside any git checkout (here a temporary directory); and a
// check prints settings whole: two that differ only in theta read apart.
TEST_F(Cli, BaselinesNamePoundbenchsCommitAndTheirCheckPrintsSettingsWhole) {
  write("tiny.toml", kTinySet);
  write("list.toml", "[[run]]\nsolver = \"moreau-jean\"\nsteps = 64\ntheta = [0.5, 1.0]\n");
  const Outcome version = run("--version");
  const std::string commit = version.out.substr(version.out.find(", commit ") + 9);
  ASSERT_EQ(run("baseline tiny.toml --settings list.toml --out base.csv").exit_code, 0);
  const std::string stored = read_text(file("base.csv"));
  EXPECT_NE(stored.find("\n# commit: " + commit.substr(0, commit.size() - 1) + " (poundbench "), std::string::npos)
      << stored << version.out;

  const Outcome o = run("baseline --check base.csv --junit junit.xml");
  EXPECT_EQ(o.exit_code, 0) << o.out << o.err;
  EXPECT_NE(o.out.find(R"(moreau-jean {"steps":64,"theta":0.5,"gamma":0.5} )"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find(R"(moreau-jean {"steps":64,"theta":1,"gamma":0.5} )"), std::string::npos) << o.out;
  const std::string xml = read_text(file("junit.xml"));
  EXPECT_NE(xml.find("<testsuites name=\"poundbench baseline --check\" tests=\"3\" failures=\"0\">"),
            std::string::npos)
      << xml;  // the reference and the two settings
}

// Issue 46 (1): --junit was checked only for being writable, so `compare r.csv --baseline
// b.csv --junit r.csv` replaced the rows (or the stored baseline), `spectrum s.toml --check
// --junit s.toml` the case set, and `--junit out.csv --out out.csv` the sweep's output, all
// with exit 0. --junit obeys the rule of every output: never an input, never another output.
TEST_F(Cli, AJunitFileThatIsAnInputOrAnotherOutputIsRefusedBeforeAnythingRuns) {
  write("tiny.toml", kTinySet);
  write("list.toml", "name = \"l\"\n[[run]]\nsolver = \"moreau-jean\"\nsteps = 16\n");
  ASSERT_EQ(run("baseline tiny.toml --out base.csv").exit_code, 0);
  write("mine.csv", six_digit_rows(read_text(file("base.csv"))));
  const std::string base = read_text(file("base.csv")), mine = read_text(file("mine.csv"));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"compare mine.csv --baseline base.csv --tolerance 1e-5 --junit mine.csv",
       "poundbench: ROWS: mine.csv: would be overwritten by --junit mine.csv (an output must not be an input)\n"},
      {"compare mine.csv --baseline base.csv --tolerance 1e-5 --junit ./base.csv",
       "poundbench: --baseline: base.csv: would be overwritten by --junit ./base.csv"},
      {"spectrum tiny.toml --check --junit tiny.toml", "poundbench: CASESET: tiny.toml: would be overwritten by --junit"},
      {"spectrum tiny.toml --check --out out.csv --junit out.csv", "poundbench: --out: out.csv: is also --junit out.csv"},
      {"spectrum tiny.toml --check --out out.csv --junit out.csv.partial",
       "poundbench: --junit: out.csv.partial: is also the partial file"},
      {"workprecision tiny.toml --settings list.toml --check --junit list.toml",
       "poundbench: --settings: list.toml: would be overwritten by --junit"},
      {"stress tiny.toml --settings list.toml --check --out s.csv --points p.csv --junit p.csv",
       "poundbench: --points: p.csv: is also --junit p.csv"},
      {"baseline --check base.csv --junit base.csv", "poundbench: --check: base.csv: would be overwritten by --junit"},
      {"baseline --check base.csv --junit tiny.toml",
       "poundbench: the baseline's case set: " + file("tiny.toml").string() + ": would be overwritten by --junit"},
  };
  for (const auto& [args, what] : cases) {
    const Outcome o = run(args);
    EXPECT_EQ(o.exit_code, 2) << args << "\n" << o.err;
    EXPECT_EQ(line_count(o.err), 1u) << args << "\n" << o.err;
    EXPECT_TRUE(o.err.starts_with(what)) << args << "\n" << o.err;
  }
  EXPECT_EQ(read_text(file("tiny.toml")), kTinySet);
  EXPECT_EQ(read_text(file("base.csv")), base);
  EXPECT_EQ(read_text(file("mine.csv")), mine);
  EXPECT_NE(read_text(file("list.toml")).find("[[run]]"), std::string::npos);
  EXPECT_EQ(files(), (std::set<std::string>{"base.csv", "list.toml", "mine.csv", "tiny.toml"}));
}

// A flag one or two edits from a real one is named; one further from every flag is not.
TEST_F(Cli, AMistypedFlagIsAnsweredWithTheNearestFlag) {
  write("tiny.toml", kTinySet);
  Outcome o = run("spectrum tiny.toml --treads 2");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.err,
            "poundbench: spectrum: unknown flag --treads (did you mean --threads?); `poundbench help spectrum` lists "
            "its flags\n");
  o = run("workprecision tiny.toml --settings x.toml --max-eror=0.1");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.err.find("unknown flag --max-eror (did you mean --max-error?)"), std::string::npos) << o.err;
  o = run("spectrum tiny.toml --frobnicate");
  EXPECT_EQ(o.err, "poundbench: spectrum: unknown flag --frobnicate; `poundbench help spectrum` lists its flags\n");
  o = run("--verison");
  EXPECT_EQ(o.err, "poundbench: unknown flag --verison (did you mean --version?); `poundbench help` lists the "
                   "subcommands\n");
  EXPECT_EQ(o.out, "");
}

}  // namespace ci_checks_tests
}  // namespace pb
