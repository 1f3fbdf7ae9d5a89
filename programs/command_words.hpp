#pragma once
// Settings::command as an argument vector. The program is started directly (posix_spawnp),
// never through a shell, so that a command means the same on every machine and in every
// sweep thread, and a value in it cannot run something else: `$`, `*`, `~`, `|`, `;`, `>`
// and `&` are ordinary characters. The rules (docs/external.md, "The command"):
//
//   - unquoted spaces, tabs and line ends separate words;
//   - '...' keeps everything inside as it is;
//   - "..." keeps everything inside but \" (a quote) and \\ (a backslash);
//   - outside quotes, \c is the character c;
//   - quoted and unquoted parts next to each other make one word: a'b c'"d" is `ab cd`,
//     and '' is an empty word.
//
// The first word is the program: looked up in PATH unless it holds a '/'.

#include <string>
#include <string_view>
#include <vector>

namespace pb::programs {

struct CommandWords {
  std::vector<std::string> words;
  std::string error;  // "command: why" when the text breaks a rule; words are then empty
};

CommandWords split_command(std::string_view command);

// Where the program of `words` is, "" if it is not there: words[0] itself when it holds a
// '/', else the first executable file of that name in PATH (what posix_spawnp runs).
std::string find_program(const std::string& program);

}  // namespace pb::programs
