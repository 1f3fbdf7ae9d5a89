#include "app/solver_flags.hpp"

#include <algorithm>
#include <array>
#include <string_view>

#include "app/errors.hpp"

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

}  // namespace

void add_solver_flags(CLI::App& command, SolverFlags& flags) {
  Settings& s = flags.settings;
  command.add_option("--solver", flags.solver, "Solver: " + solver_names() + " (see `poundbench solvers`)")
      ->capture_default_str();
  command.add_option("--variant", s.variant, "Solver variant (default: the solver's own)");
  command.add_option("--steps", s.steps, "Time-steppers: steps per shortest period N, h = T_min/N (0: default)")
      ->capture_default_str();
  command.add_option("--wh", s.wh,
                     "Time-steppers: the step as w_max h, w_max = 2 pi / T_min (> 0 replaces --steps; 0: use --steps)")
      ->capture_default_str();
  command.add_option("--theta", s.theta, "Moreau-Jean theta")->capture_default_str();
  command.add_option("--gamma", s.gamma, "Moreau-Jean activation look-ahead")->capture_default_str();
  command.add_option("--tol-scale", s.tol_scale, "Event-driven: factor on every internal tolerance")
      ->capture_default_str();
  command.add_option("--step-cap", s.step_cap, "Most steps or events per run (0: the solver's own cap)")
      ->capture_default_str();
  command.add_option("--time-limit", s.time_limit, "Most wall-clock seconds per run (0: none)")
      ->capture_default_str();
}

std::string as_flag_message(const std::string& field_reason) {
  // Solvers name a field either as its Settings member or as its flag without the dashes.
  static constexpr std::array<std::string_view, 9> kFlags = {"variant",  "steps",    "wh",         "theta",  "gamma",
                                                             "tol-scale", "step-cap", "time-limit", "samples"};
  const std::size_t colon = field_reason.find(':');
  if (colon == std::string::npos) return field_reason;
  std::string flag = field_reason.substr(0, colon);
  std::replace(flag.begin(), flag.end(), '_', '-');
  if (flag == "history-samples") flag = "samples";
  if (std::find(kFlags.begin(), kFlags.end(), flag) == kFlags.end()) return field_reason;
  return "--" + flag + field_reason.substr(colon);
}

const SolverInfo& checked_solver(const SolverFlags& flags) {
  const SolverInfo* solver = find_solver(flags.solver);
  if (!solver) throw BadInput("--solver: unknown solver '" + clip(flags.solver) + "' (known: " + solver_names() + ")");
  if (std::string bad = solver->check(flags.settings); !bad.empty()) throw BadInput(as_flag_message(bad));
  return *solver;
}

}  // namespace pb::app
