#pragma once
// What the two TOML readers share (case sets, cases/case_set.cpp; settings lists,
// studies/settings_list.cpp): a file read whole, and TOML syntax errors as one line,
// "<file>:<line>: syntax: <reason>". Each reader throws its own error type, so both
// helpers take it as a template argument.

#include <toml++/toml.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#include "cases/case.hpp"

namespace pb {

// The whole file as text; Error("<file>: cannot read: <why>") when it cannot be read.
template <class Error>
std::string read_input_file(const std::filesystem::path& file) {
  const std::string source = file.string();
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw Error(source + ": cannot read: is a directory");
  std::FILE* f = std::fopen(source.c_str(), "rb");
  if (f == nullptr) throw Error(source + ": cannot read: " + std::strerror(errno));
  std::string text;
  char buffer[1 << 14];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throw Error(source + ": cannot read: read error");
  return text;
}

// The TOML document, or Error for its first syntax error (the reason clipped: toml++ may
// quote the file's own text).
template <class Error>
toml::table parse_toml(std::string_view text, std::string_view source) {
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    std::string reason = clip(e.description(), kMaxEchoedReason);
    for (char& c : reason)
      if (c == '\n') c = ' ';
    throw Error(std::string(source) + ":" + std::to_string(e.source().begin.line) + ": syntax: " + reason);
  }
}

}  // namespace pb
