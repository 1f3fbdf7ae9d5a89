#pragma once
// Text helpers every floor of the project uses in its messages and outputs: user text echoed
// in a one-line error, and numbers written so that they read back exactly.

#include <array>
#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>

namespace pb {

// A reason that quotes user text inside a library's or a solver's own words (a TOML
// syntax error, a solver's check) is clipped as a whole, at this length.
inline constexpr std::size_t kMaxEchoedReason = 200;
// User text (a key, a value, a name) as echoed in a message: at most `max` bytes, cut at a
// character boundary and marked with "...", so that a 10 MB key gives a one-line error;
// control characters become '?'.
inline constexpr std::size_t kMaxEchoed = 60;
std::string clip(std::string_view text, std::size_t max = kMaxEchoed);

// The shortest decimal text that reads back to exactly x (to_chars without a format; a float
// as its own shortest text: 0.85f as 0.85, not as the double 0.8500000238...).
template <typename T>
std::string shortest_text(T x) {
  std::array<char, 64> buffer{};
  const auto [end, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
  if (error != std::errc{}) return {};
  return {buffer.data(), end};
}

// shortest_text(x) for a double; NaN gives "".
std::string format_number(double x);

}  // namespace pb
