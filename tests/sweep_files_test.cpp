// What the sweep commands do with their files and messages when something is off: a
// second sweep on one output, an output that is not a regular file, a final write that
// fails, an interrupt whose line goes to a file, and paths that a shell would read as
// commands; and their plain lines where stderr is a pipe. Run as a separate process, as
// tests/cli_test.cpp does.

#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "output/sweep_watch.hpp"
#include "tests/cli_fixture.hpp"

extern char** environ;

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace sweep_files_tests {

constexpr const char* kTinyList = R"(name = "tiny"
[[run]]
solver = "moreau-jean"
steps = 64
)";

class SweepFiles : public Cli {
 protected:
  // poundbench with `args` (no shell), stdout to `out`, stderr to `log`, SIGINT at its
  // default whatever the test runner inherited; returns its pid.
  pid_t spawn(std::vector<std::string> args, const fs::path& log, const char* out = "/dev/null") const {
    return spawn_poundbench(std::move(args), dir_, out, log);
  }

  // Writes kTinySet as tiny.toml and starts a spectrum of it to out.csv that is still on its
  // first points for as long as a test needs it to run: moreau-jean at 1e8 steps per shortest
  // period (7e8 steps, past the default cap) takes about 10 s a point. Returns its pid.
  pid_t spawn_slow_spectrum(const fs::path& log) const {
    write("tiny.toml", kTinySet);
    return spawn({"spectrum", "tiny.toml", "--out", "out.csv", "--solver", "moreau-jean", "--steps", "100000000",
                  "--step-cap", "2000000000", "--threads", "1"},
                 log);
  }

  // Waits (at most 20 s) until `file` exists; then a little longer, so that the sweep
  // that writes it is past its checks and watching for signals.
  static bool wait_for(const fs::path& file) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!fs::exists(file) && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    return fs::exists(file);
  }

  // Stops a sweep at once (two SIGINTs: the second abandons the running points) and
  // returns its exit code (-1: it did not end within 20 s, and was killed).
  static int abandon(pid_t pid) {
    ::kill(pid, SIGINT);
    std::this_thread::sleep_for(std::chrono::milliseconds(400));  // signals do not queue
    ::kill(pid, SIGINT);
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    pid_t waited = 0;
    while ((waited = ::waitpid(pid, &status, WNOHANG)) == 0 && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (waited == 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return -1;
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
};

// While a sweep runs, another on the same --out is refused (exit 2, one line naming the
// holder's pid) and touches nothing; the lock goes with the first sweep however it ends,
// here abandoned by a second Ctrl-C, and the output is free again.
TEST_F(SweepFiles, ASecondSweepOnTheSameOutputIsRefusedNamingTheHolder) {
  const pid_t first = spawn_slow_spectrum(file("first.log"));
  ASSERT_TRUE(wait_for(file("out.csv.partial")));
  const std::string partial = read_text(file("out.csv.partial"));

  const Outcome second = run("spectrum tiny.toml --out out.csv");
  EXPECT_EQ(second.exit_code, 2);
  EXPECT_EQ(line_count(second.err), 1u) << second.err;
  EXPECT_NE(second.err.find("--out: out.csv: another sweep (pid " + std::to_string(first) + ")"), std::string::npos)
      << second.err;
  EXPECT_EQ(read_text(file("out.csv.partial")), partial);
  EXPECT_FALSE(fs::exists(file("out.csv")));

  EXPECT_EQ(abandon(first), 130);
  EXPECT_EQ(files(), (std::set<std::string>{"tiny.toml", "first.log", "out.csv.partial"}));
  const Outcome after = run("spectrum tiny.toml --out out.csv");
  EXPECT_EQ(after.exit_code, 0) << after.err;
  EXPECT_EQ(files(), (std::set<std::string>{"tiny.toml", "first.log", "out.csv"}));
}

// The lock of a study that writes to stdout is in the current directory; a lock file that
// a killed sweep left (no process holds it) does not stop the next one, which removes it.
TEST_F(SweepFiles, AStudyOnStdoutIsLockedTooAndALeftLockFileIsTakenOver) {
  write("tiny.toml", kTinySet);
  write("list.toml", kTinyList);
  const int fd = ::open(file("poundbench-stress.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::write(fd, "4242\n", 5), 5);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);  // as a running sweep holds it
  const Outcome held = run("stress tiny.toml --settings list.toml");
  EXPECT_EQ(held.exit_code, 2);
  EXPECT_EQ(line_count(held.err), 1u) << held.err;
  EXPECT_NE(held.err.find("another sweep (pid 4242)"), std::string::npos) << held.err;
  EXPECT_EQ(held.out, "");

  ::close(fd);  // as a killed sweep leaves it: the file, no lock
  const Outcome free = run("stress tiny.toml --settings list.toml");
  EXPECT_EQ(free.exit_code, 0) << free.err;
  EXPECT_EQ(files(), (std::set<std::string>{"tiny.toml", "list.toml"}));
}

// A device or a pipe as a sweep's output is refused before anything runs: the sweep could
// neither rename its output into place nor keep a partial file beside it (as root,
// `--out /dev/full` used to create /dev/full.partial).
TEST_F(SweepFiles, AnOutputThatIsNotARegularFileIsRefusedBeforeTheSweep) {
  write("tiny.toml", kTinySet);
  write("list.toml", kTinyList);
  ASSERT_EQ(::mkfifo(file("pipe").c_str(), 0644), 0);
  const bool had_partial = fs::exists("/dev/full.partial");
  for (const char* args : {"spectrum tiny.toml --out /dev/full", "spectrum tiny.toml --out pipe",
                                 "workprecision tiny.toml --settings list.toml --out pipe",
                                 "stress tiny.toml --settings list.toml --out o.csv --points /dev/full"}) {
    const Outcome o = run(args);
    EXPECT_EQ(o.exit_code, 2) << args;
    EXPECT_EQ(line_count(o.err), 1u) << args << "\n" << o.err;
    EXPECT_NE(o.err.find("not a regular file"), std::string::npos) << args << "\n" << o.err;
    EXPECT_EQ(files(), (std::set<std::string>{"tiny.toml", "list.toml", "pipe"})) << args;
  }
  if (!had_partial) {
    EXPECT_FALSE(fs::exists("/dev/full.partial"));
  }
}

// A final write that fails says why, and that the rows are in the partial file, from
// which a rerun writes the output without running anything again.
TEST_F(SweepFiles, AFailedFinalWriteNamesTheReasonAndKeepsTheRows) {
  write("tiny.toml", kTinySet);
  int status = 0;
  ASSERT_GT(::waitpid(spawn({"spectrum", "tiny.toml"}, file("err.txt"), "/dev/full"), &status, 0), 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = read_text(file("err.txt"));
  EXPECT_EQ(line_count(err), 1u) << err;
  EXPECT_NE(err.find("stdout: write failed: No space left on device"), std::string::npos) << err;
  EXPECT_NE(err.find("poundbench-spectrum.partial.csv"), std::string::npos) << err;
  EXPECT_EQ(line_count(read_text(file("poundbench-spectrum.partial.csv"))), 7u);
  fs::remove(file("err.txt"));

  const Outcome resumed = run("spectrum tiny.toml");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(line_count(resumed.out), 7u);
  EXPECT_EQ(files(), (std::set<std::string>{"tiny.toml"}));
}

// Terminal control sequences only go to a terminal: the line of an interrupted sweep, in a
// log file, is plain text.
TEST_F(SweepFiles, TheInterruptedLineHasNoTerminalControlWhenStderrIsAFile) {
  const fs::path log = file("sweep.log");
  const pid_t pid = spawn_slow_spectrum(log);
  ASSERT_TRUE(wait_for(file("out.csv.partial")));
  EXPECT_EQ(abandon(pid), 130);
  const std::string err = read_text(log);
  // The first SIGINT ends the running points at their next look at the clock and the
  // sweep says how far it got; where that look comes later than the second SIGINT (an
  // unoptimised build), the sweep is abandoned and says so. Either line is plain text.
  EXPECT_TRUE(err == "poundbench: interrupted after 0 of 6 points; the finished rows are in out.csv.partial\n" ||
              err == "poundbench: interrupted; the finished rows are in out.csv.partial\n")
      << err;
  EXPECT_EQ(err.find('\033'), std::string::npos);
  EXPECT_EQ(err.find('\r'), std::string::npos);
}

// Rows reach the partial file in batches (output/resumable_sweep.cpp), each within 0.6 s of
// finishing: a finished row is written while the next point runs, however long that one
// takes, and a kill (which no handler sees) leaves it in the file. Point 0, a wall at
// n_free = 1, takes milliseconds at 1e5 steps per period (seconds under AddressSanitizer);
// point 1, a chain of 100 bodies at n_free = 100, far longer than the test.
TEST_F(SweepFiles, AFinishedRowReachesThePartialFileWhileTheNextPointRuns) {
  write("two.toml", R"(name = "fast then slow"
[defaults]
pulse = "sine"
directivity = "normal"
eps = 0.5
pi3 = 0.5
pi2 = 1
[[family]]
name = "fast"
scene = "wall"
n_free = 1
[[family]]
name = "slow"
scene = "chain"
bodies = 100
pi5 = 0.1
pi6 = 1
n_free = 100
)");
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = spawn({"spectrum", "two.toml", "--out", "out.csv", "--solver", "moreau-jean", "--steps", "100000",
                           "--step-cap", "2000000000", "--threads", "1"},
                          file("log.txt"));
  const fs::path partial = file("out.csv.partial");
  while (line_count(read_text(partial)) < 2 && std::chrono::steady_clock::now() - start < std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  const std::string rows = read_text(partial);
  ASSERT_EQ(line_count(rows), 2u) << rows;
  EXPECT_NE(rows.find("\nfast,0,wall,"), std::string::npos) << rows;
  // The point's own time and the program's start come on top of the 0.6 s: generous
  // bounds for a loaded machine, where the row would otherwise wait for point 1's end.
  EXPECT_LT(seconds, 10.0);
}

// A path is never part of a shell command: the baseline's provenance (git) runs from an
// argument vector, so a directory named like a command injection is only a directory.
TEST_F(SweepFiles, ABaselinePathIsNeverRunAsAShellCommand) {
  write("tiny.toml", kTinySet);
  const std::string odd = "q'; touch INJECTED; echo '";
  fs::create_directories(file(odd));
  const Outcome o = run("baseline tiny.toml --out \"" + odd + "/b.csv\"");
  EXPECT_EQ(o.exit_code, 0) << o.err;
  EXPECT_FALSE(fs::exists(file("INJECTED")));
  EXPECT_FALSE(fs::exists(file(odd) / "INJECTED"));
  EXPECT_NE(read_text(file(odd) / "b.csv").find("\n# commit: "), std::string::npos);
}

// On a pipe (a batch job's log, mpirun's forwarding) a sweep writes plain lines: progress
// every ten seconds (none in a sweep this short) and what it wrote, last.
TEST_F(SweepFiles, OnAPipeTheLastLineSaysHowManyRowsWentWhereInHowLong) {
  write("tiny.toml", kTinySet);
  const std::string command = "cd '" + dir_.string() + "' && '" POUNDBENCH_EXE "' spectrum tiny.toml --out out.csv 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string err;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe)) err += buffer;
  EXPECT_EQ(::pclose(pipe), 0) << err;
  ASSERT_EQ(line_count(err), 1u) << err;
  EXPECT_EQ(err.rfind("poundbench: wrote 6 rows to out.csv in ", 0), 0u) << err;
  EXPECT_TRUE(err.ends_with(" s\n")) << err;
  EXPECT_EQ(err.find('\033'), std::string::npos);
}

// The plain progress line: done of total, time so far and, from this run's rate (not the
// tasks a resumed run found done), about how long is left.
TEST(ProgressLine, SaysDoneOfTotalTheTimeSoFarAndAboutHowLongIsLeft) {
  EXPECT_EQ(app::progress_line("spectrum", "points", 1234, 23820, 0, 12.0, false),
            "spectrum: 1234/23820 points, 12 s, about 4 min left");  // 22586 left at 102.8/s: 220 s
  EXPECT_EQ(app::progress_line("stress", "runs", 2000, 3000, 1000, 50.0, false),
            "stress: 2000/3000 runs, 50 s, about 50 s left");
  EXPECT_EQ(app::progress_line("spectrum", "points", 10, 100000, 0, 4000.0, false),
            "spectrum: 10/100000 points, 67 min, about 11110.0 h left");
  EXPECT_EQ(app::progress_line("spectrum", "points", 500, 1000, 500, 30.0, false), "spectrum: 500/1000 points, 30 s");
  EXPECT_EQ(app::progress_line("spectrum", "points", 7, 10, 0, 15.0, true),
            "spectrum: 7/10 points, 15 s, stopping (a second Ctrl-C abandons the running ones)");
}

}  // namespace sweep_files_tests
}  // namespace pb
