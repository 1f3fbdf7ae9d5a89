#include "programs/command_words.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>

namespace pb::programs {

CommandWords split_command(std::string_view command) {
  CommandWords out;
  std::string word;
  bool in_word = false;  // a word has started (it may be empty: '')
  const auto fail = [&](const char* why) {
    out.words.clear();
    out.error = std::string("command: ") + why;
    return out;
  };
  for (std::size_t i = 0; i < command.size(); ++i) {
    const char c = command[i];
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      if (in_word) out.words.push_back(std::move(word));
      word.clear();
      in_word = false;
    } else if (c == '\'') {
      const std::size_t end = command.find('\'', i + 1);
      if (end == std::string_view::npos) return fail("a single quote (') is not closed");
      word.append(command.substr(i + 1, end - i - 1));
      in_word = true;
      i = end;
    } else if (c == '"') {
      in_word = true;
      for (++i;; ++i) {
        if (i >= command.size()) return fail("a double quote (\") is not closed");
        if (command[i] == '"') break;
        if (command[i] == '\\' && i + 1 < command.size() && (command[i + 1] == '"' || command[i + 1] == '\\')) ++i;
        word += command[i];
      }
    } else if (c == '\\') {
      if (i + 1 == command.size()) return fail("ends in a backslash (\\ escapes the next character)");
      word += command[++i];
      in_word = true;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (in_word) out.words.push_back(std::move(word));
  if (out.words.empty()) return fail("no program (give the program and its arguments, e.g. \"python3 adapter.py\")");
  if (out.words.front().empty()) return fail("the program's name is empty");
  return out;
}

namespace {

bool executable_file(const std::string& path) {
  struct stat st {};
  return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(path.c_str(), X_OK) == 0;
}

}  // namespace

std::string find_program(const std::string& program) {
  if (program.find('/') != std::string::npos) return executable_file(program) ? program : std::string();
  // posix_spawnp's search: PATH, or the system's default path when PATH is not set.
  std::string path;
  if (const char* env = std::getenv("PATH")) {
    path = env;
  } else {
    path.resize(confstr(_CS_PATH, nullptr, 0));
    if (!path.empty()) confstr(_CS_PATH, path.data(), path.size());
    path = path.c_str();
  }
  for (std::size_t start = 0; start <= path.size();) {
    const std::size_t end = std::min(path.find(':', start), path.size());
    const std::string dir = end > start ? path.substr(start, end - start) : std::string(".");  // "" is the current dir
    if (const std::string candidate = dir + "/" + program; executable_file(candidate)) return candidate;
    start = end + 1;
  }
  return {};
}

}  // namespace pb::programs
