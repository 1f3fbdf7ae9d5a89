#pragma once
// Runs one fuzz input in a child process, so that a crash, a sanitizer abort, a hang or a
// runaway allocation is a finding about that input and never takes the test down with it.

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace pb::fuzz {

// A hang is measured in work, not in time: a child spinning in a loop spends CPU, and its CPU
// seconds are the same on an idle machine and on one loaded ten times over, where a wall-clock
// bound fails inputs that merely waited for a core (issue 46). A child blocked without
// spending CPU (a pipe, a sleep) is caught by a wall clock as generous as a backstop can be.
struct ChildLimits {
  double seconds = 5;                    // CPU: the child's own and its waited-for children's; then SIGKILL
  std::size_t max_rss_bytes = 2UL << 30;  // resident memory; then SIGKILL
  double wall_seconds = 0;               // then SIGKILL; 0: the default, wall_limit()

  // Six times the CPU limit, at least 30 s, and under ctest's 180 s TIMEOUT for a fuzz test.
  double wall_limit() const { return wall_seconds > 0 ? wall_seconds : std::min(std::max(30.0, 6 * seconds), 150.0); }
};

struct ChildOutcome {
  bool exited = false;     // else killed by a signal (ours or its own)
  int exit_code = -1;
  int signal = 0;
  bool timed_out = false;  // we killed it at a time limit: CPU (spinning) or wall (blocked)
  bool blocked = false;    // the wall clock's: it spent no more than its CPU limit
  bool over_memory = false;  // we killed it at the memory limit
  double seconds = 0;
  std::string out, err;    // the first kKeep bytes of each
  std::size_t out_size = 0, err_size = 0;  // every byte written
  static constexpr std::size_t kKeep = 1 << 20;

  // "exit 3", "signal 11 (Segmentation fault)", "hang: killed after 5 s", ...
  std::string describe() const;
};

// Forks; the child runs `body` with stdout and stderr on pipes, then _exit(0) (no atexit
// handlers: the parent's test framework must not run twice).
ChildOutcome run_in_child(const std::function<void()>& body, const ChildLimits& limits);

// run_in_child with the fuzz targets' report: the child writes what `body` returns on stdout,
// or "EXC <type>: <what>" when it throws, so that the parent tells an exception no reader may
// let out from a refusal the body reports itself.
ChildOutcome report_in_child(const std::function<std::string()>& body, const ChildLimits& limits);

// What a program gets besides its arguments: its stdin (a file's contents; empty: /dev/null,
// so that no program ever waits on the test's terminal) and variables added to the
// environment ("NAME=value").
struct ProgramInput {
  std::string stdin_text;
  std::vector<std::string> environment;
};

// Forks and executes `program` with `args` (argv[1..]) in `dir`.
ChildOutcome run_program(const std::string& program, const std::vector<std::string>& args,
                         const std::filesystem::path& dir, const ChildLimits& limits, const ProgramInput& input = {});

// The first line that a sanitizer prints, if `err` holds a sanitizer report.
std::string sanitizer_line(const std::string& err);

}  // namespace pb::fuzz
