#pragma once
// A solver's variants as a table of configurations, each with a `name`: the engines' (ODE,
// Bullet, MuJoCo, DART, Simbody) look theirs up by name, list the names in their messages,
// and describe and check a run's settings the same way.

#include <array>
#include <cstddef>
#include <exception>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "kit/fixed_step.hpp"
#include "kit/named_values.hpp"
#include "kit/solver.hpp"

namespace pb {

// An engine's named configurations (kVariants in its variants.hpp) and the name of the one a
// run without --variant gets.
template <class Config, std::size_t N>
struct VariantTable {
  std::array<Config, N> configs;
  std::string_view default_name;

  // The configuration called `name` ("" is the default), if the table has one.
  std::optional<Config> find(std::string_view name) const {
    if (name.empty()) name = default_name;
    for (const Config& c : configs)
      if (c.name == name) return c;
    return std::nullopt;
  }
};

template <class Config, std::size_t N>
VariantTable(std::array<Config, N>, std::string_view) -> VariantTable<Config, N>;

// The table's names, comma-separated, for a message.
template <class Config, std::size_t N>
std::string names_of(const VariantTable<Config, N>& table) {
  std::string out;
  for (const Config& c : table.configs) {
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
template <class Config, std::size_t N>
std::string describe_variant(const VariantTable<Config, N>& table, const Settings& settings, int default_steps) {
  const std::optional<Config> config = table.find(settings.variant);
  NamedValues out;
  out.add("variant", config ? std::string_view(config->name) : std::string_view(settings.variant));
  if (!config) return out.add("unknown", true).json();
  if (takes_steps(*config)) add_step(out, settings, default_steps);
  add_config(out, *config, settings);
  return out.json();
}

// What every such engine's check() asks first: a known variant, and where it steps, a valid
// step and contact activation rule. "" when they are fine; the engine checks its own after.
template <class Config, std::size_t N>
std::string check_variant(std::string_view solver, const VariantTable<Config, N>& table, const Settings& settings,
                          int default_steps) {
  const std::optional<Config> config = table.find(settings.variant);
  if (!config)
    return "variant: unknown " + std::string(solver) + " variant '" + settings.variant + "' (one of " +
           names_of(table) + ")";
  if (!takes_steps(*config)) return {};
  if (std::string bad = check_step(settings, default_steps); !bad.empty()) return bad;
  if constexpr (requires { config->activation; }) return check_activation(config->activation, settings);
  return {};
}

// solve() of such an engine whose bodies' springs are linear (MuJoCo, DART, Simbody): a failed
// run for an unknown variant, a yielding system refused saying `why_linear`, else
// run(system, settings, config), an exception out of the engine a failed run with its message
// (after `error_prefix`).
template <class Config, std::size_t N>
Result solve_linear_variant(const VariantTable<Config, N>& table, const System& system, const Settings& settings,
                            std::string_view why_linear, Result (*run)(const System&, const Settings&, const Config&),
                            std::string_view error_prefix = {}) {
  const std::optional<Config> config = table.find(settings.variant);
  if (!config) return failed("unknown variant '" + settings.variant + "'");
  if (system.yields()) return yielding_refused(why_linear);
  try {
    return run(system, settings, *config);
  } catch (const std::exception& e) {
    return failed(std::string(error_prefix) + e.what());
  }
}

}  // namespace pb
