// `poundbench` under mpiexec with two ranks (sweep/processes.hpp, sweep/mpi_sweep.hpp): the
// rows, summaries and resumed results of one process, bad inputs that end every rank.
// Skipped, saying so, when poundbench was built without MPI.

#include <gtest/gtest.h>

#include <initializer_list>
#include <set>
#include <string>
#include <string_view>

#include "tests/cli_fixture.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace mpi_cli_tests {

// Two ranks on whatever cores there are, as root too (CI runs as root); `timeout` ends a
// job that hangs, which is a failure of its own.
#ifdef POUNDBENCH_MPIEXEC
constexpr const char* kTwoRanks =
    "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 60 '" POUNDBENCH_MPIEXEC "' -np 2 --oversubscribe";
#else
constexpr const char* kTwoRanks = "";
#endif

const std::string kSmoke = std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/smoke.toml";
const std::string kSmokeList = std::string(POUNDBENCH_SOURCE_DIR) + "/cases/settings/smoke.toml";

class Mpi : public Cli {
 protected:
  void SetUp() override {
#ifndef POUNDBENCH_MPIEXEC
    GTEST_SKIP() << "poundbench was built without MPI (CMake found no OpenMPI): nothing to run under mpiexec";
#endif
    Cli::SetUp();
  }
};

// The poundbench lines of stderr (mpiexec adds its own banner when a rank fails).
std::size_t poundbench_lines(const std::string& err) {
  std::size_t n = 0;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("poundbench: ", 0) == 0) ++n;
  return n;
}

TEST_F(Mpi, TwoRanksWriteTheRowsOfOneProcess) {
  ASSERT_EQ(run("spectrum '" + kSmoke + "' --out one.csv --threads 2").exit_code, 0);
  const Outcome o = run("spectrum '" + kSmoke + "' --out two.csv --threads 1", kTwoRanks);
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(o.out, "");
  EXPECT_EQ(o.err.rfind("poundbench: wrote 40 rows to two.csv in ", 0), 0u) << o.err;  // and nothing else
  EXPECT_EQ(line_count(o.err), 1u) << o.err;
  EXPECT_EQ(files(), (std::set<std::string>{"one.csv", "two.csv"}));
  const CsvTable one(read_text(file("one.csv"))), two(read_text(file("two.csv")));
  ASSERT_EQ(one.rows.size(), 40u);
  EXPECT_EQ(two.columns, one.columns);
  EXPECT_EQ(two.without(kTimingColumns).rows, one.without(kTimingColumns).rows);
}

// As a rank that died leaves it: some rows, in completion order, and a line cut short.
TEST_F(Mpi, TwoRanksResumeAPartialFileRunningOnlyTheMissingPoints) {
  ASSERT_EQ(run("spectrum '" + kSmoke + "' --out full.csv --threads 2").exit_code, 0);
  CsvTable full(read_text(file("full.csv")));
  std::string partial = CsvTable::line(full.columns) + "\n";
  const std::set<std::size_t> kept = {33, 0, 17, 5, 39, 21};
  for (std::size_t point : kept) {
    full.at(point, "seconds") = "12345";
    partial += CsvTable::line(full.rows[point]) + "\n";
  }
  write("out.csv.partial", partial + CsvTable::line(full.rows[8]).substr(0, 40));

  const Outcome o = run("spectrum '" + kSmoke + "' --out out.csv --threads 1", kTwoRanks);
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(files(), (std::set<std::string>{"full.csv", "out.csv"}));
  CsvTable out(read_text(file("out.csv")));
  EXPECT_EQ(out.without(kTimingColumns).rows, full.without(kTimingColumns).rows);
  for (std::size_t point = 0; point < full.rows.size(); ++point)
    EXPECT_EQ(out.at(point, "seconds") == "12345", kept.count(point) == 1) << point;
}

TEST_F(Mpi, StudiesOnTwoRanksWriteTheSummariesAndRunsOfOneProcess) {
  for (const std::string command : {"workprecision", "stress"}) {
    const std::string args = command + " '" + kSmoke + "' --settings '" + kSmokeList + "'";
    ASSERT_EQ(run(args + " --out sum1.csv --points runs1.csv --threads 2").exit_code, 0);
    const Outcome o = run(args + " --out sum2.csv --points runs2.csv --threads 1", kTwoRanks);
    ASSERT_EQ(o.exit_code, 0) << o.err;
    const CsvTable runs1(read_text(file("runs1.csv"))), runs2(read_text(file("runs2.csv")));
    EXPECT_EQ(runs1.rows.size(), 40u * 5u) << command;  // the truth and 4 settings
    EXPECT_EQ(runs2.without(kTimingColumns).rows, runs1.without(kTimingColumns).rows) << command;
    const CsvTable sum1(read_text(file("sum1.csv"))), sum2(read_text(file("sum2.csv")));
    const std::vector<std::string_view> cpu =
        command == "stress" ? std::vector<std::string_view>{"cpu_median_s", "cpu_median_low_s", "cpu_median_high_s"}
                            : std::vector<std::string_view>{"cpu_median_s", "cpu_mean_s", "cpu_median_low_s",
                                                            "cpu_median_high_s", "repetitions"};
    EXPECT_EQ(sum2.without(cpu).rows, sum1.without(cpu).rows) << command;
    EXPECT_EQ(files(), (std::set<std::string>{"sum1.csv", "runs1.csv", "sum2.csv", "runs2.csv"})) << command;
  }
}

// Whether every rank or the leader alone finds the fault, every rank ends with exit code 2
// (none is left waiting) and poundbench prints its one line once. (mpiexec itself takes
// two seconds to end a job whose ranks failed, hence only the two kinds.)
TEST_F(Mpi, ABadInputEndsEveryRankWithOneLine) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"spectrum missing.toml --out out.csv", "missing.toml"},           // every rank
      {"spectrum '" + kSmoke + "' --out no-such-dir/out.csv", "--out"},  // the leader alone
  };
  for (const auto& [args, names] : bad) {
    const Outcome o = run(args, kTwoRanks);
    EXPECT_EQ(o.exit_code, 2) << args << "\n" << o.err;
    EXPECT_EQ(poundbench_lines(o.err), 1u) << args << "\n" << o.err;
    EXPECT_NE(o.err.find(names), std::string::npos) << args << "\n" << o.err;
    EXPECT_EQ(o.out, "") << args;
    EXPECT_EQ(files(), std::set<std::string>{}) << args;
  }
}

}  // namespace mpi_cli_tests
}  // namespace pb
