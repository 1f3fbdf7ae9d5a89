#pragma once
// Compact JSON written straight out as text, byte for byte what nlohmann's dump(-1) writes for the
// same object (programs/case_document.cpp says why): the case documents of both scenes.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/load.hpp"

namespace pb::programs {

// Compact JSON (no spaces), the commas placed as values follow one another.
class CompactJson {
 public:
  explicit CompactJson(std::string& out) : out_(out) {}

  CompactJson& open(char bracket) {
    separate();
    out_ += bracket;
    first_ = true;
    return *this;
  }
  CompactJson& close(char bracket) {
    out_ += bracket;
    first_ = false;
    return *this;
  }
  // The keys are this file's literals: plain ASCII, nothing to escape.
  CompactJson& key(std::string_view k) {
    separate();
    out_ += '"';
    out_ += k;
    out_ += "\":";
    first_ = true;
    return *this;
  }
  CompactJson& number(double x) {
    separate();
    if (!std::isfinite(x)) {  // the dump's spelling of a number JSON has not
      out_ += "null";
      return *this;
    }
    std::array<char, 64> buffer;  // the dump's own buffer size
    const char* end = nlohmann::detail::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
    out_.append(buffer.data(), static_cast<std::size_t>(end - buffer.data()));
    return *this;
  }
  CompactJson& integer(long long n) {
    separate();
    std::array<char, 24> buffer;
    const char* end = std::to_chars(buffer.data(), buffer.data() + buffer.size(), n).ptr;
    out_.append(buffer.data(), static_cast<std::size_t>(end - buffer.data()));
    return *this;
  }
  CompactJson& boolean(bool b) {
    separate();
    out_ += b ? "true" : "false";
    return *this;
  }
  CompactJson& null() {
    separate();
    out_ += "null";
    return *this;
  }
  CompactJson& string(std::string_view s) {
    separate();
    // Printable ASCII but '"' and '\' is the dump's text as it is; anything else (a control
    // character, a byte of UTF-8 or not) is escaped or replaced by the library, as before.
    const bool plain =
        std::all_of(s.begin(), s.end(), [](char ch) { return ch >= 0x20 && ch <= 0x7E && ch != '"' && ch != '\\'; });
    if (plain) {
      out_ += '"';
      out_ += s;
      out_ += '"';
    } else {
      using Ordered = nlohmann::ordered_json;
      out_ += Ordered(std::string(s)).dump(-1, ' ', false, Ordered::error_handler_t::replace);
    }
    return *this;
  }
  CompactJson& numbers(const std::vector<double>& xs) {
    open('[');
    for (double x : xs) number(x);
    return close(']');
  }

 private:
  void separate() {
    if (!first_) out_ += ',';
    first_ = false;
  }
  std::string& out_;
  bool first_ = true;
};

// The load by its kind (docs/external.md, "The kinds of load"), as the object's next value.
void write_load(CompactJson& j, const Pulse& p);

}  // namespace pb::programs
