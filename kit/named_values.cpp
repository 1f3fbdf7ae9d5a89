#include "kit/named_values.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "cases/text.hpp"
#include "kit/solver.hpp"

namespace pb {

namespace {

// JSON has no infinity or NaN; the strings keep what they mean (max_vel = "inf": no limit).
template <typename T>
std::string json_number(T x) {
  if (std::isfinite(x)) return shortest_text(x);
  return std::isnan(x) ? "\"nan\"" : x > 0 ? "\"inf\"" : "\"-inf\"";
}

// A JSON string; a byte that is not UTF-8 (a name from a file, an argument) becomes U+FFFD,
// so that the settings of a run can always be written.
// Printable ASCII other than '"' and '\\' is written as it is, the text nlohmann's dump gives
// it, without that detour (a json value and its serializer): describe() of Moreau-Jean's
// settings 7.3 k -> 3.9 k instructions (callgrind), and a poundbench.run call describes
// its settings three times.
std::string json_string(std::string_view text) {
  const bool plain = std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7f && c != '"' && c != '\\'; });
  if (plain) return '"' + std::string(text) + '"';
  return nlohmann::json(std::string(text)).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace

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

NamedValues& NamedValues::add(std::string_view name, long long value) { return add_raw(name, shortest_text(value)); }

NamedValues& NamedValues::add(std::string_view name, bool value) { return add_raw(name, value ? "true" : "false"); }

NamedValues& NamedValues::add(std::string_view name, std::string_view text) {
  return add_raw(name, json_string(text));
}

void add_stiffness(NamedValues& out, const Settings& settings, double pi_term) {
  if (!(settings.k_contact > 0.0 && settings.stiffness == 0.0)) out.add("stiffness", pi_term);
  if (settings.k_contact > 0.0) out.add("k_contact", settings.k_contact);
}

}  // namespace pb
