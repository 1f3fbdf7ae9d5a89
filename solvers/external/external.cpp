#include "solvers/external/external.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include <signal.h>
#include <string.h>

#include "cases/text.hpp"
#include "programs/command_words.hpp"
#include "programs/process.hpp"
#include "programs/protocol.hpp"
#include "kit/named_values.hpp"

namespace pb::external {

using programs::case_document;
using programs::CaseDocument;
using programs::CommandWords;
using programs::exchange;
using programs::find_program;
using programs::last_lines;
using programs::printable_line;
using programs::ProgramLimits;
using programs::ProgramRun;
using programs::read_answer;
using programs::run_program;
using programs::split_command;

namespace {

bool known_variant(std::string_view v) { return v.empty() || v == kPerPoint || v == kPersistent; }

std::string known_variants() {
  return std::string(kPerPoint) + " (default), " + std::string(kPersistent);
}

std::string seconds_text(double s) {
  std::ostringstream out;
  out << s;
  return out.str();
}

// "; stderr: line | line" with the last lines the program wrote there, or "".
std::string stderr_note(const ProgramRun& run) {
  const std::string tail = last_lines(run.err_tail, kStderrLines);
  return tail.empty() ? std::string() : "; stderr: " + clip(tail, 1000);
}

std::string signal_text(int sig) {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 32))
  if (const char* abbrev = sigabbrev_np(sig)) return std::to_string(sig) + " (SIG" + abbrev + ")";
#endif
  return std::to_string(sig);
}

// What the program's run says, when it is not an answer to read: "" when it is one.
Status outcome(const ProgramRun& run, const Settings& settings, std::string& why) {
  if (!run.spawn_error.empty()) {
    why = "command: cannot start " + run.spawn_error;
    return Status::failed;
  }
  if (run.stopped) {
    why = "stopped (the sweep was interrupted): the program was ended";
    return Status::time_limit;
  }
  if (run.timed_out) {
    // The limit as given (the point's), not what was left of it for this solve.
    const double given = settings.point_time_limit > 0.0 ? settings.point_time_limit : settings.time_limit;
    why = "more than " + format_number(given) + " s of wall time: the program had not answered " +
          seconds_text(kGraceSeconds) + " s after it and was ended" + stderr_note(run);
    return Status::time_limit;
  }
  if (run.output_cut) {
    why = "the program wrote more than " + std::to_string(kMaxAnswerBytes >> 20) + " MB to stdout and was ended";
    return Status::failed;
  }
  if (!run.protocol_error.empty()) {
    why = run.protocol_error + "; it was ended (the next point starts it again)" + stderr_note(run);
    return Status::failed;
  }
  // A persistent program that ended between two cases, or while it had one: not "stdout: empty".
  const std::string unanswered = run.unanswered ? " before it answered this case" : "";
  if (!run.exited) {
    why = "the program was ended by signal " + signal_text(run.signal) + unanswered + stderr_note(run);
    return Status::failed;
  }
  if (run.exit_code != 0 || run.unanswered) {
    why = "the program exited with code " + std::to_string(run.exit_code) + unanswered + stderr_note(run);
    return Status::failed;
  }
  return Status::ok;
}

// A persistent program's own solve_seconds against the CPU its threads ran in the exchange
// (issue 48: a program that reported 1e-9 s won every target at 0.00 us): past the noise
// (1 ms, and half the measured time: a program's reading and writing of the documents are in
// the exchange, not in its solve), the run cannot vouch for its cost, and says so. A program
// that solves in a process of its own (not counted) is flagged too: docs/external.md says so.
void doubt_reported_time(Result& r, double exchange_cpu) {
  if (r.status != Status::ok || !std::isfinite(r.solve_seconds) || !std::isfinite(exchange_cpu)) return;
  if (std::abs(r.solve_seconds - exchange_cpu) <= 1e-3 + 0.5 * exchange_cpu) return;
  if (!r.doubt.empty()) r.doubt += "; ";
  r.doubt += "it reports solve_seconds " + format_number(r.solve_seconds) + " s where its process ran " +
             format_number(exchange_cpu) + " s of CPU in the exchange (the row's cost is the latter)";
}

}  // namespace

std::string cannot_start(const Settings& settings, CommandWords& command, Status& status) {
  status = Status::failed;
  if (!known_variant(settings.variant))
    return "variant: unknown '" + clip(settings.variant) + "' (known: " + known_variants() + ")";
  command = settings.in_process ? CommandWords{{"(in process)"}, {}} : split_command(settings.command);
  if (!command.error.empty()) return command.error;
  status = Status::time_limit;
  if (settings.stop && settings.stop->load(std::memory_order_relaxed))
    return "stopped (the sweep was interrupted) before the program started";
  return {};
}

Exchanged exchange_document(const std::string& document, const CommandWords& command, const Settings& settings) {
  Exchanged out;
  ProgramLimits limits;
  limits.kill_after = settings.time_limit > 0.0 ? settings.time_limit + kGraceSeconds : 0.0;
  // The answer is read within the same limit as the program ran (a run's limit is the whole
  // run's: a 40 MB answer took 13.7 s to parse after it).
  const auto start = std::chrono::steady_clock::now();
  // (1e9 s: a limit beyond it is none, and its time_point would overflow.)
  out.deadline = limits.kill_after > 0.0 && limits.kill_after < 1e9
                     ? start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                   std::chrono::duration<double>(limits.kill_after))
                     : std::chrono::steady_clock::time_point::max();
  limits.stop = settings.stop;
  limits.max_output = kMaxAnswerBytes;
  ProgramRun& run = out.run;
  if (settings.in_process) {
    // The answer of a Python callable; what it throws is the point's failed row (the sweep's).
    run.out = (*settings.in_process)(document, out.call_seconds);
    run.exited = true;
    run.exit_code = 0;
  } else if (settings.variant == kPersistent) {
    run = exchange(command.words, std::string_view(document).substr(0, document.size() - 1), limits, out.startup);
  } else {
    run = run_program(command.words, document, limits);
  }
  out.status = outcome(run, settings, out.why);
  return out;
}

std::string answer_refused(const Exchanged& x, const std::string& bad, Status& status) {
  // Past the deadline the answer was cut off by the limit, whatever else it lacked.
  status = std::chrono::steady_clock::now() > x.deadline ? Status::time_limit : Status::failed;
  return bad + stderr_note(x.run);
}

Result solve(const System& system, const Settings& settings) {
  Result r;
  const auto finish = [&](Status status, std::string message) {
    r.status = status;
    r.message = std::move(message);
    r.pi1 = r.t_max = std::numeric_limits<double>::quiet_NaN();
    return r;
  };
  CommandWords command;
  Status status = Status::ok;
  if (std::string why = cannot_start(settings, command, status); !why.empty()) return finish(status, why);
  const CaseDocument document = case_document(system, settings);
  if (!document.error.empty()) return finish(Status::failed, document.error);
  if (settings.steps > 0 || settings.wh > 0.0 || settings.h_s > 0.0) {
    r.step = time_step(system, settings, 1);
    if (std::string bad = step_problem(system, r.step); !bad.empty()) return finish(Status::failed, bad);
  }
  const Exchanged x = exchange_document(document.text, command, settings);
  if (!x.why.empty()) {
    finish(x.status, x.why);
  } else if (std::string bad = read_answer(x.run.out, system, settings, r, x.deadline); !bad.empty()) {
    std::string message = answer_refused(x, bad, status);
    finish(status, std::move(message));
  }
  // Whatever the program wrote reaches the row as one printable line of UTF-8 (its message,
  // its stderr, a line quoted in an error): a row's reader (report) refuses anything else.
  r.message = printable_line(r.message);
  r.startup_seconds = x.startup;
  if (settings.in_process) r.solve_seconds = x.call_seconds;  // timed around the call, whatever it says
  // The row's cost is poundbench's clock: the program's CPU (a persistent one's in the exchange)
  // on top of this thread's. What a persistent program says of itself is kept beside it.
  const double cpu = x.run.cpu_seconds;
  r.child_cpu_seconds = std::isfinite(cpu) ? cpu : 0.0;
  if (settings.variant == kPersistent && !settings.in_process) doubt_reported_time(r, cpu);
  return r;
}

std::string describe(const Settings& settings) {
  NamedValues out;
  if (!settings.name.empty()) out.add("name", settings.name);
  out.add("command", settings.command);
  if (settings.h_s > 0.0)
    out.add("h_s", settings.h_s);
  else if (settings.wh > 0.0)
    out.add("wh", settings.wh);
  else if (settings.steps > 0)
    out.add("steps", settings.steps);
  return out.json();
}

std::string check(const Settings& settings) {
  if (!known_variant(settings.variant))
    return "variant: unknown '" + settings.variant + "' (known: " + known_variants() + ")";
  if (!settings.in_process) {  // a Python callable has no command
    if (settings.command.empty())
      return "command: required by solver external (the program and its arguments, e.g. \"python3 adapter.py\")";
    const CommandWords command = split_command(settings.command);
    if (!command.error.empty()) return command.error;
    const std::string& program = command.words.front();
    if (find_program(program).empty())
      return "command: " + (program.find('/') == std::string::npos
                                ? "program '" + clip(program) + "' not found in PATH"
                                : "'" + clip(program) + "' is not an executable file");
  }
  if (settings.steps < 0) return "steps: must be >= 1 (0: the program's own step)";
  if (!(settings.wh >= 0.0) || !std::isfinite(settings.wh)) return "wh: must be finite and > 0 (0: use steps)";
  if (settings.wh > 0.0 && settings.steps > 0) return "wh: give steps or wh, not both";
  return {};
}

std::vector<VariantInfo> variant_list() {
  return {{kPerPoint, "a process per point: the case as JSON on its stdin, the answer as JSON on its stdout "
                      "(docs/external.md)"},
          {kPersistent, "one program per sweep worker, started once, answering a stream of cases: one JSON "
                        "document per line each way, after a ready line (--persistent; docs/external.md)"}};
}

}  // namespace pb::external
