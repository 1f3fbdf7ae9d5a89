#pragma once
// One run of another program: its input written to its stdin, its stdout and the end of
// its stderr read back, the program ended at a deadline or when a stop flag is set, and
// reaped. The only code of solvers/ that starts a process: the external solver's whole
// point is to run a program poundbench does not link (docs/external.md).
//
// What a sweep needs of it, with several threads calling at once:
//   - no descriptor leaks: every pipe is close-on-exec from its creation (pipe2), so a
//     program another thread starts at the same moment inherits none of this one's pipes,
//     and the child closes every descriptor above 2 before exec (closefrom), so it also
//     inherits none that other code opened without close-on-exec;
//   - no SIGPIPE: a program that exits without reading its input must not kill poundbench,
//     so the writing thread blocks SIGPIPE while it writes (a sweep's worker for as long as it
//     works: ThreadSessionsEnd) and takes back the one a write raised (a thread-directed
//     signal, so other threads are untouched);
//   - no zombie: the child is always waited for, on every path out (an exception too);
//   - a deadline and a stop flag: the program runs in a process group of its own, and the
//     whole group (a script and what it started) gets SIGKILL.

#include <atomic>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace pb::programs {

// The variant of a solver whose program is started once per sweep worker and answers a stream
// of cases, a line each way (exchange below): the external solver's `--persistent`.
inline constexpr std::string_view kPersistent = "persistent";

struct ProgramLimits {
  double kill_after = 0.0;  // wall seconds from the start; 0: none
  const std::atomic<bool>* stop = nullptr;  // ends the program once set
  std::size_t max_output = 0;               // stdout bytes; beyond, the program is ended
};

struct ProgramRun {
  std::string spawn_error;  // it could not be started (then nothing below holds)
  bool exited = false;      // ended by itself: exit_code holds; else by the signal
  int exit_code = -1;
  int signal = 0;
  bool timed_out = false;     // ended at kill_after
  bool stopped = false;       // ended because the stop flag was set
  bool output_cut = false;    // ended for writing more than max_output
  bool input_refused = false; // it closed its stdin before reading all of the input
  // Persistent mode (exchange): it ended (exited, or by a signal: exited and exit_code, or
  // signal, say how) before it answered the case, which may not have been sent.
  bool unanswered = false;
  // Persistent mode: why it broke the protocol (a line on its stdout before the case was sent,
  // or before it read it: not the case's answer); then it was ended. "" when it did not.
  std::string protocol_error;
  std::string out;            // its stdout
  std::string err_tail;       // the last lines of its stderr (at most kErrTail bytes)
  double seconds = 0.0;       // wall time from the start to its end
  // Its CPU time, user and system, with its waited-for children; persistent mode: what its
  // threads ran from the case's sending to its answer (its process CPU clock; its children not
  // counted), NaN where the clock cannot be read, 0 where it did not answer.
  double cpu_seconds = 0.0;
};

// What is kept of stderr: its end, enough for a traceback's last lines.
inline constexpr std::size_t kErrTail = 4096;

ProgramRun run_program(const std::vector<std::string>& argv, std::string_view input, const ProgramLimits& limits);

// Ends every program run_program is running now, with its group: for a process about to
// _Exit (a sweep abandoned by a second Ctrl-C), whose programs, in groups of their own, the
// terminal's signal does not reach and no destructor will end.
void end_running_programs();

// A persistent program (docs/external.md, "Persistent mode"): started once per thread and
// command, it answers a stream of cases, one line each way. After its start it writes one ready
// line ({"version": 1, "ready": true}, protocol.hpp's ready_line_problem) so that its start-up
// is timed apart from any solve. Each exchange writes `line` (one line, without its end) and
// reads one line back into ProgramRun::out; every other field says, as run_program's do, why
// there was no answer (spawn_error, timed_out, stopped, output_cut; unanswered with exited or
// signal when it ended by itself; protocol_error), and then the program has been ended, with
// its group, and the next exchange starts it again.
//
// A line is the case's answer only if the program wrote it after it read the case: one already
// on its stdout before the case is sent (a second answer to the last case, written late), or
// written while the whole case still sat unread in its stdin, is a protocol_error. Once the
// program itself has exited, nothing it left behind (a child holding its stdout or stderr, in
// a session of its own where the group's SIGKILL does not reach it) holds the exchange: its
// pipes are read for what is there and closed.
// kill_after counts from the exchange's start (the program's start included, on the first).
// `startup_seconds` is set to the start's wall seconds on the exchange that started it, NaN on
// the others. cpu_seconds is what the program's threads ran between the case and its answer.
ProgramRun exchange(const std::vector<std::string>& argv, std::string_view line, const ProgramLimits& limits,
                    double& startup_seconds);
// Ends the calling thread's persistent programs: their stdin closed, each given kDrainAfterExit
// to exit, then ended with its group. A sweep's worker calls it as it ends (ThreadSessionsEnd);
// a thread that never does ends them as it exits.
void end_thread_sessions();
// A sweep's worker, from its start to its end: its programs are ended as it ends, and SIGPIPE
// stays blocked on it from its first write to a program until then (not set and restored around
// each exchange: three system calls a point). A SIGPIPE one of its writes raised is taken back
// at once; any other is delivered as the scope ends.
struct ThreadSessionsEnd {
  ThreadSessionsEnd();
  ThreadSessionsEnd(const ThreadSessionsEnd&) = delete;
  ThreadSessionsEnd& operator=(const ThreadSessionsEnd&) = delete;
  ~ThreadSessionsEnd();
};

// The last `lines` lines of text (without a trailing line end), each line end as " | ", for
// a one-line message.
std::string last_lines(std::string_view text, int lines);

}  // namespace pb::programs
