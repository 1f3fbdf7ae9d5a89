#include "solvers/named_values.hpp"

#include <array>
#include <charconv>
#include <cmath>

#include <nlohmann/json.hpp>

namespace pb {

namespace {

template <typename T>
std::string shortest(T x) {
  // Without a format argument to_chars gives the shortest text that round-trips.
  std::array<char, 64> buffer{};
  const auto [end, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
  if (error != std::errc{}) return {};
  return {buffer.data(), end};
}

// JSON has no infinity or NaN; the strings keep what they mean (max_vel = "inf": no limit).
template <typename T>
std::string json_number(T x) {
  if (std::isfinite(x)) return shortest(x);
  return std::isnan(x) ? "\"nan\"" : x > 0 ? "\"inf\"" : "\"-inf\"";
}

// A JSON string; a byte that is not UTF-8 (a name from a file, an argument) becomes U+FFFD,
// so that the settings of a run can always be written.
std::string json_string(std::string_view text) {
  return nlohmann::json(std::string(text)).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace

std::string format_number(double x) { return std::isnan(x) ? std::string() : shortest(x); }

NamedValues& NamedValues::add_raw(std::string_view name, std::string_view json_value) {
  if (json_.size() > 1) json_ += ',';
  json_ += json_string(name);
  json_ += ':';
  json_ += json_value;
  return *this;
}

NamedValues& NamedValues::add(std::string_view name, double value) { return add_raw(name, json_number(value)); }

NamedValues& NamedValues::add(std::string_view name, float value) {
  return add_raw(name, json_number(value));
}

NamedValues& NamedValues::add(std::string_view name, long long value) { return add_raw(name, shortest(value)); }

NamedValues& NamedValues::add(std::string_view name, bool value) { return add_raw(name, value ? "true" : "false"); }

NamedValues& NamedValues::add(std::string_view name, std::string_view text) {
  return add_raw(name, json_string(text));
}

}  // namespace pb
