#pragma once
// A solver's variants as a table of configurations, each with a `name`: the engines' (ODE,
// Bullet, MuJoCo) look theirs up by name and list the names in their messages the same way.

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace pb {

// The configuration called `name` ("" is `default_name`), if the table has one.
template <class Config>
std::optional<Config> find_named(std::span<const Config> table, std::string_view name, std::string_view default_name) {
  if (name.empty()) name = default_name;
  for (const Config& c : table)
    if (c.name == name) return c;
  return std::nullopt;
}

// The table's names, comma-separated, for a message.
template <class Config>
std::string names_of(std::span<const Config> table) {
  std::string out;
  for (const Config& c : table) {
    if (!out.empty()) out += ", ";
    out += c.name;
  }
  return out;
}

}  // namespace pb
