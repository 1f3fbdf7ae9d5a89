#include "frontend/solver_flags.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>
#include <vector>

#include "cases/fields.hpp"
#include "cases/system.hpp"
#include "cases/text.hpp"
#include "frontend/errors.hpp"
#include "programs/process.hpp"
#include "kit/settings_fields.hpp"
#include "solvers/registry.hpp"

namespace pb::app {

namespace {

std::string solver_names() {
  std::string names;
  for (const SolverInfo& s : solvers()) {
    if (!names.empty()) names += ", ";
    names += s.name;
  }
  return names;
}

// The own settings of every solver (SolverInfo::own_settings) as flags, each name once: a
// value goes to Settings::own at its index in the chosen solver's list. CLI11 runs the options'
// callbacks in the order they were added, after the parse, so --solver is known by then.
void add_own_setting_flags(CLI::App& command, SolverFlags& flags) {
  std::vector<std::string_view> added;
  for (const SolverInfo& solver : solvers())
    for (const OwnSetting& own : solver.own_settings) {
      if (std::find(added.begin(), added.end(), own.name) != added.end()) continue;
      added.push_back(own.name);
      const std::string name(own.name);
      command.add_option_function<double>(
          flag_of(own.name),
          [&flags, name](double x) { set_own_setting(flags, name, x); },
          std::string(own.help) + " (" + std::string(solver.name) + "'s own)");
    }
}

}  // namespace

void set_own_setting(SolverFlags& flags, std::string_view name, double x) {
  const SolverInfo* chosen = find_solver(flags.solver);
  if (!chosen) return;  // checked_solver names the unknown solver
  if (const auto i = own_setting_index(chosen->own_settings, name))
    flags.settings.own[*i] = x;
  else
    flags.undeclared = flag_of(name);
}

void add_solver_flags(CLI::App& command, SolverFlags& flags) {
  Settings& s = flags.settings;
  command.add_option("--solver", flags.solver, "Solver: " + solver_names() + " (see `poundbench solvers`)")
      ->capture_default_str();
  CLI::Option* variant = command.add_option("--variant", s.variant, "Solver variant (default: the solver's own)");
  command
      .add_flag_callback(
          "--persistent", [&s] { s.variant = std::string(programs::kPersistent); },
          "External: start the program once per worker and send it every case, a line each way "
          "(--variant persistent; docs/external.md)")
      ->excludes(variant);
  for (const SettingField& f : kSettingFields) {
    const std::string flag = flag_of(f.name), help(f.help);
    CLI::Option* option = f.number    ? command.add_option(flag, s.*f.number, help)
                          : f.integer ? command.add_option(flag, s.*f.integer, help)
                          : f.count   ? command.add_option(flag, s.*f.count, help)
                                      : command.add_option(flag, s.*f.text, help);
    option->capture_default_str();
  }
  add_own_setting_flags(command, flags);
  command.add_flag("--monitor", s.monitor,
                   "Solve each point once more, untimed, with the time-steppers' monitor on: energy_excess, "
                   "the restitution range and gap_rate_max, and the verdict's energy and restitution criteria");
}

std::string as_flag_message(const std::string& field_reason) {
  // Solvers name a field either as its Settings member or as its flag without the dashes.
  const std::size_t colon = field_reason.find(':');
  if (colon == std::string::npos) return field_reason;
  std::string field = field_reason.substr(0, colon);
  std::replace(field.begin(), field.end(), '-', '_');
  const auto known = [&](std::string_view name) { return field == name; };
  if (field == "history_samples" || field == "samples") return "--samples" + field_reason.substr(colon);
  if (!known("variant") && std::none_of(kSettingFields.begin(), kSettingFields.end(),
                                        [&](const SettingField& f) { return known(f.name); }))
    return field_reason;
  return flag_of(field) + field_reason.substr(colon);
}

const SolverInfo& checked_solver(const SolverFlags& flags, const GivenSolverFlag& given) {
  const SolverInfo* solver = find_solver(flags.solver);
  if (!solver) throw BadInput("--solver: unknown solver '" + clip(flags.solver) + "' (known: " + solver_names() + ")");
  if (!flags.undeclared.empty())
    throw BadInput(flags.undeclared + ": not used by solver " + std::string(solver->name) + " (another solver's own setting)");
  if (std::string bad = solver->check(flags.settings); !bad.empty()) throw BadInput(as_flag_message(bad));
  if (given) {
    const auto field_given = [&](std::string_view field) { return given(flag_of(field)); };
    if (std::string bad = unused_setting(*solver, flags.settings, field_given); !bad.empty())
      throw BadInput(as_flag_message(bad));
  }
  return *solver;
}

void check_step_bound(const Case& c, const Settings& settings) {
  if (!(settings.wh > 0.0) && settings.steps_per_sample <= 0) return;  // N steps per shortest period always meet it
  const System system = make_system(c);
  if (std::string bad = step_rule_problem(system, settings); !bad.empty()) throw BadInput(as_flag_message(bad));
  if (std::string bad = step_problem(system, time_step(system, settings, 1)); !bad.empty())
    throw BadInput("--wh: " + bad);
}

void add_estimate_flags(CLI::App& command, ErrorEstimate& estimate, bool sweep) {
  if (sweep)
    command.add_flag("--estimate-error", estimate.on,
                     "Fixed-step solvers: estimate each point's relative error of Pi1 from a companion solve at twice "
                     "the step (about half a solve more; the error_estimate column), which `resolved` needs");
  command
      .add_option("--target-error", estimate.target_error,
                  "The largest error estimate (relative, of Pi1) of a resolved run" +
                      std::string(sweep ? " (with --estimate-error)" : ""))
      ->capture_default_str();
}

void check_estimate_flags(const CLI::App& command, const ErrorEstimate& estimate, bool sweep) {
  if (!(estimate.target_error > 0.0) || !std::isfinite(estimate.target_error))
    throw BadInput("--target-error: must be a finite number > 0 (a relative error: 0.01 is 1 %)");
  if (sweep && command.count("--target-error") && !estimate.on)
    throw BadInput("--target-error: only used with --estimate-error");
}

const SolverInfo& checked_solver(const SolverFlags& flags, const CLI::App& command) {
  return checked_solver(flags, [&](std::string_view flag) { return command.count(std::string(flag)) > 0; });
}

}  // namespace pb::app
