#pragma once
// The two JSON documents of the external solver's protocol (docs/external.md; their JSON
// Schemas are docs/external/case.schema.json and answer.schema.json): the case poundbench
// writes to the program's stdin, and the answer the program writes to its stdout. Both
// directions are here, so that one file owns the format: poundbench's side (case_document,
// read_answer) and a program's side (read_case, answer_document), which `poundbench
// adapter` uses to answer as an external program itself.
//
// The case is the System every solver gets (cases/system.hpp), in physical units: bodies
// with their mass, stiffness and damping, the contacts with their gaps, eps, the ground
// load as a function, t_end, the step a time-stepper should take and the limits of the run.
// Numbers are written so that they read back to the same double (nlohmann's shortest
// round-trip form), so a program that reads them loses nothing: `poundbench adapter`
// reproduces the in-process Pi1 bit for bit.

#include <chrono>
#include <string>
#include <string_view>

#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb::programs {

inline constexpr std::string_view kProtocol = "poundbench-external";
// Raised when a document changes in a way an existing program or reader would misread.
// Adding a load kind (issue 21's recorded accelerograms: "record") is not such a change:
// a program refuses a kind it does not know, by its answer (docs/external.md).
inline constexpr int kVersion = 1;

// The case for `system` solved with `settings`: "" and the text, or an error ("field:
// why") for a system JSON cannot carry (a NaN or infinite number).
struct CaseDocument {
  std::string text;
  std::string error;
};
CaseDocument case_document(const System& system, const Settings& settings);

// The answer read into `result`: status, message, Pi1 (from the history of u0 when only that
// is given), counts and measurements; a history is kept when settings.history_samples > 0.
// Returns "" or "answer: field: why" (the answer is then not used): a key twice, nesting
// deeper than any answer's, a message over 10,000 bytes, a time outside the run (a history's
// times must also not fall), or still being read at `deadline` (the run's time limit).
std::string read_answer(std::string_view text, const System& system, const Settings& settings, Result& result,
                        std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

// A persistent program's first line (docs/external.md, "Persistent mode"): "" when it is the
// ready line, a JSON object whose "ready" is true and "version" 1 (found by its parse, not in
// the text: {"ready": false} and a bare "ready" are no ready line); else why, in one line.
std::string ready_line_problem(std::string_view line);

// Text a program wrote (its answer's message, its stderr, a line quoted in an error) as one
// printable line of valid UTF-8, for a row: a byte that is not UTF-8 becomes U+FFFD; a control
// character (C0, DEL, C1: a line end, an escape sequence's ESC), a line or paragraph separator
// and the invisible format characters (bidirectional overrides, zero widths) become '?'.
std::string printable_line(std::string_view text);

// A program's side: the system and the settings a case document carries (the step as
// steps_per_period, or as wh from step, step_cap, time_limit, history_samples, monitor).
// Throws std::invalid_argument("field: why").
struct CaseRead {
  System system;
  Settings settings;
};
CaseRead read_case(std::string_view text);

// A Result as an answer document (one line): every count and measurement the Result has,
// and the history of u0 when it has one.
std::string answer_document(const Result& result, const System& system);

}  // namespace pb::programs
