#pragma once
// The external solver: another program, run once per point (`--solver external --command
// "PROGRAM ARGS"`). It gets the case as one JSON document on its stdin and answers with
// one on its stdout (programs/protocol.hpp, docs/external.md), so that a solver
// enters poundbench without being linked into it: an OpenSees model, a Python script.
//
// Why a process per point by default, and a long-lived program only when asked: a
// process that crashes, hangs or leaks takes one point with it and nothing else, a sweep's
// threads need no locking between them, and the program stays a plain filter that a user
// tries by hand (`program < case.json`). Its cost, measured by wrapping poundbench itself
// (`poundbench adapter`, docs/external.md), is a few milliseconds per point: for the
// compiled solvers it dominates (they take microseconds), for the programs this is for
// (a Python integrator, an FE model) it does not, except for the start of Python with its
// imports (85 to 90 % of a SciPy point: issue 37), which the persistent variant pays once per
// worker, its program answering a stream of cases, one line each way (programs/process.hpp,
// exchange). Running programs and their protocol are the room programs/, this folder the solver.
//
// Everything that can go wrong with a program is a row, never a stopped sweep: it cannot
// be started (failed), it exits with a code other than 0 or is ended by a signal (failed,
// with its stderr's last lines), its answer is not one (failed, naming the field), it
// passes the time limit (time-limit: it is ended), the sweep is stopped (time-limit:
// "stopped", it is ended).

#include <chrono>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "programs/command_words.hpp"
#include "programs/process.hpp"
#include "kit/solver.hpp"

namespace pb::external {

// The variants: a process per point (the default), or one program per sweep worker that
// answers a stream of cases, a line each way (`--persistent`, `persistent = true`).
inline constexpr std::string_view kPerPoint = "per-point";
using programs::kPersistent;

// A program asked to stop at Settings::time_limit gets this much longer to write its
// answer before it is ended (a Python program's start alone takes 0.1 to 0.3 s of it).
inline constexpr double kGraceSeconds = 0.5;
// Its stdout, at most: the history of u0 at run's largest --samples (1e6) is ~40 MB. Read
// and parsed within the run's time limit (programs/protocol.hpp, read_answer).
inline constexpr std::size_t kMaxAnswerBytes = std::size_t{64} << 20;
// The lines of stderr a failure's message quotes.
inline constexpr int kStderrLines = 5;

Result solve(const System& system, const Settings& settings);
// The buildings scene (cases/buildings.hpp): the same program, per point or persistent, or the
// Python callable, with the scene's documents (programs/buildings_protocol.hpp). Its cost clock
// is the sweep's thread (BuildingsResult has no field for a child's CPU): the program's own
// CPU is not in a buildings row's cpu_seconds yet, its wall time is in seconds.
buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings);
// What solve_buildings reads (SolverInfo::buildings_settings), besides the variant.
inline constexpr std::string_view kBuildingsSettings[] = {"command", "name", "steps", "wh", "h_s", "step_cap", "time_limit"};
std::string describe(const Settings& settings);
std::string check(const Settings& settings);
std::vector<VariantInfo> variant_list();

// The exchange of one case document, shared by both scenes (external.cpp).
//
// "" when a run may start, else why not and its status in `status` (an unknown variant, a
// command that does not split, a sweep already stopped); `command` the program's words.
std::string cannot_start(const Settings& settings, programs::CommandWords& command, Status& status);
struct Exchanged {
  programs::ProgramRun run;
  double startup = std::numeric_limits<double>::quiet_NaN();       // a persistent program's start
  double call_seconds = std::numeric_limits<double>::quiet_NaN();  // a Python callable's call
  std::chrono::steady_clock::time_point deadline;                  // its answer is read by then
  Status status = Status::ok;
  std::string why;  // "": run.out is an answer to read; else why there is none, status says what
};
// The document (ending in '\n') to the program, per point or persistent, or to the callable.
Exchanged exchange_document(const std::string& document, const programs::CommandWords& command,
                            const Settings& settings);
// The message of a row whose answer was refused (`bad`, its field and why) with the program's
// stderr; status failed, or time_limit when the reading passed the deadline.
std::string answer_refused(const Exchanged& x, const std::string& bad, Status& status);

}  // namespace pb::external
