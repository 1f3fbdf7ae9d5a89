#pragma once
// A CSV line built field by field, with no string per field: a sweep formats a row per point
// (the paper set's 23 820 rows, 45 fields each), and a string per field was an allocation for
// most numbers. Numbers are written shortest round-trip (std::to_chars), NaN as an empty
// field; text quoted as RFC 4180 asks only when it holds a comma, a quote, CR or LF.

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>

namespace pb {

// text as one CSV field, appended to out: as it is, or quoted with its quotes doubled.
inline void append_csv_field(std::string& out, std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) {
    out += text;
    return;
  }
  out += '"';
  for (char ch : text) {
    if (ch == '"') out += '"';
    out += ch;
  }
  out += '"';
}

class LineBuilder {
 public:
  LineBuilder() { line_.reserve(512); }
  void text(std::string_view s) {
    separate();
    append_csv_field(line_, s);
  }
  void number(double x) {
    separate();
    if (!std::isnan(x)) append(x);
  }
  void count(long long n) {
    separate();
    append(n);
  }
  // Numbers in one field, separated by ';' (no quoting needed); NaN as an empty item.
  template <class Range>
  void numbers(const Range& xs) {
    separate();
    bool first = true;
    for (double x : xs) {
      if (!first) line_ += ';';
      first = false;
      if (!std::isnan(x)) append(x);
    }
  }
  std::string take() { return std::move(line_); }

 private:
  void separate() {
    if (!first_) line_ += ',';
    first_ = false;
  }
  template <class T>
  void append(T x) {
    std::array<char, 64> buffer{};
    const auto [end, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
    if (error == std::errc{}) line_.append(buffer.data(), end);
  }
  std::string line_;
  bool first_ = true;
};

}  // namespace pb
