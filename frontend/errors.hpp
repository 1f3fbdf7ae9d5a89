#pragma once
// The command line's two kinds of failure, which main() turns into exit codes:
// BadInput (exit 2) is the user's to fix and its what() is the one line printed; any other
// exception is a runtime failure (exit 1).

#include <exception>
#include <stdexcept>
#include <string>

namespace pb::app {

struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The exit code main() gives a failure: 2 for the user's input (BadInput, a case-set or
// settings-list error), 1 for anything else. Processes::agree uses it for every rank.
int exit_code_of(const std::exception& e);

// A failure's message as the one line main() prints after "poundbench: " (and the Python
// module raises): a message echoes what the user wrote (a key, a value, a file name), and
// not every source clips it (pb::clip), so each ": "-separated part, and then the line, is
// bounded so that the field and the reason survive a 10 MB key; line ends become spaces.
std::string one_line(const std::string& message);

// The exit code of a sweep command that a signal stopped (its partial file is kept).
inline constexpr int kInterrupted = 130;

}  // namespace pb::app
