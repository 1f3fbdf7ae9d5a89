#pragma once
// A solver's variants as a table of configurations, each with a `name`: the engines' (ODE,
// Bullet, MuJoCo, DART, Simbody) look theirs up by name, list the names in their messages,
// and describe and check a run's settings the same way.

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "solvers/fixed_step.hpp"
#include "solvers/named_values.hpp"
#include "solvers/solver.hpp"

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

// Whether a configuration steps at a fixed step (Settings::steps, wh): every one, unless its
// type says otherwise (Simbody's Hunt-Crossley chooses its own steps).
template <class Config>
bool takes_steps(const Config& config) {
  if constexpr (requires { config.time_stepper(); })
    return config.time_stepper();
  else
    return true;
}

// describe() of an engine with a variant table: the variant's name, the step (steps = N or
// wh = X) where it takes one, then its configuration's own settings, as the engine's
// add_config(NamedValues&, const Config&, const Settings&) writes them (found beside Config).
template <class Config>
std::string describe_variant(const std::optional<Config>& config, const Settings& settings, int default_steps) {
  NamedValues out;
  out.add("variant", config ? std::string_view(config->name) : std::string_view(settings.variant));
  if (!config) return out.add("unknown", true).json();
  if (takes_steps(*config)) add_step(out, settings, default_steps);
  add_config(out, *config, settings);
  return out.json();
}

// What every such engine's check() asks first: a known variant, and where it steps, a valid
// step and contact activation rule. "" when they are fine; the engine checks its own after.
template <class Config>
std::string check_variant(std::string_view solver, const std::optional<Config>& config, std::span<const Config> table,
                          const Settings& settings, int default_steps) {
  if (!config)
    return "variant: unknown " + std::string(solver) + " variant '" + settings.variant + "' (one of " +
           names_of(table) + ")";
  if (!takes_steps(*config)) return {};
  if (std::string bad = check_step(settings, default_steps); !bad.empty()) return bad;
  if constexpr (requires { config->activation; }) return check_activation(config->activation, settings);
  return {};
}

}  // namespace pb
