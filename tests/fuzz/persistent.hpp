#pragma once
// The fuzz target issue 46 asked for in "persistent answers in streams": persistent external
// programs (docs/external.md, "Persistent mode") that misbehave in the stream. An input is the
// Python source of such a program: a ready line, right or wrong (`{"ready": false}`, a bare
// "ready", two of them, one cut in two, one late, none), then per case one of a pool of actions:
// an answer; an answer and a second line late or at once; a line cut in two; bytes that are not
// UTF-8, escape sequences and control characters in the answer or on stderr; an exit or a
// SIGKILL between cases or during one; a sleep past the limit; a child left holding its stdout
// and stderr, in its group or in a session of its own (setsid); a closed stdout; an answer of
// 200,000 keys with one twice, or a 100,000-byte message. A Python driver (any Python 3, not the
// module) runs `poundbench spectrum` over four points with the program at --time-limit 1 and
// checks:
//
//   * poundbench exits 0 within 90 s (four points of 1 s and their grace, and a loaded machine:
//     the children left behind sleep 100 s, so a run that waits for them is caught);
//   * a row per point, its status one of the statuses, its message one printable line;
//   * the rows are UTF-8 (read strictly) and CSV (Python's reader).
//
// The driver ends the children the program left behind (their pids are in a file), only those
// still running `sleep 100`.

#include <optional>
#include <string>

#include "tests/fuzz/child.hpp"
#include "tests/fuzz/mutator.hpp"

namespace pb::fuzz {

// Whether the driver can run: a Python 3 interpreter was found at configure time.
bool persistent_available();
// The property the program `source` (Python) violates as a persistent external program, or nothing.
std::optional<std::string> check_persistent(const std::string& source, const ChildLimits& limits);
// A program of a ready action and three case actions drawn from the pools in persistent.cpp.
std::string make_persistent_program(Rng& rng);

}  // namespace pb::fuzz
