#pragma once
// What the two TOML readers share (case sets, cases/case_set.cpp; settings lists,
// studies/settings_list.cpp), besides reading the file (cases/input_file.hpp): TOML syntax
// errors as one line, "<file>:<line>: syntax: <reason>". Each reader throws its own error
// type, so the helper takes it as a template argument.

#include <toml++/toml.h>

#include <string>
#include <string_view>

#include "cases/case.hpp"
#include "cases/input_file.hpp"
#include "cases/text.hpp"

namespace pb {

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
