#pragma once
// The flags that pick a solver and fill its Settings, shared by `run` and `spectrum`.

#include <functional>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "cases/case.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "sweep/sweep.hpp"

namespace pb::app {

struct SolverFlags {
  std::string solver{reference_solver().name};  // the default: the reference
  // `run` and `spectrum` solve each point once, unmonitored, unless --monitor asks for the
  // monitor's measurements (one more, untimed solve: run_point). The second pass was 53 % of
  // the paper set's instructions through Moreau-Jean, and only `stress` judges what it measures.
  Settings settings = [] {
    Settings s;
    s.monitor = false;
    return s;
  }();
  // An own setting (SolverInfo::own_settings) given that the chosen solver does not declare:
  // its flag, which checked_solver refuses.
  std::string undeclared;
};

void add_solver_flags(CLI::App& command, SolverFlags& flags);

// An own setting given (a flag, a Python keyword), once flags.solver is known: into
// settings.own at its index in that solver's list, or kept as `undeclared`.
void set_own_setting(SolverFlags& flags, std::string_view name, double x);

// The named solver, after SolverInfo::check accepted the settings and no flag of
// kit/settings_fields.hpp that `given` ("--theta") says was given is one the solver does
// not use (pb::unused_setting); throws BadInput.
using GivenSolverFlag = std::function<bool(std::string_view flag)>;
const SolverInfo& checked_solver(const SolverFlags& flags, const GivenSolverFlag& given = {});
// The same, `given` being the flags of `command`.
const SolverInfo& checked_solver(const SolverFlags& flags, const CLI::App& command);

// Throws BadInput ("--wh: step: h = ... is longer than the pulse period ...") when the step
// the settings give is beyond pb::step_problem's bound for this case: `run` refuses it before
// running, where a sweep's row says failed. Likewise --steps-per-sample on a pulse
// (pb::step_rule_problem: the rule needs a record's samples).
void check_step_bound(const Case& c, const Settings& settings);

// "field: reason" from a check() with the field turned into its flag, e.g. "--tol-scale: ...".
std::string as_flag_message(const std::string& field_reason);

// --target-error (the largest error estimate a resolved run may have, kit/verdict.hpp) and,
// on a sweep (`spectrum`, `workprecision`, `stress`), --estimate-error, which a sweep's
// estimate needs: it costs a companion solve at twice the step per point (sweep/sweep.hpp).
// `run` estimates whenever it can, so it has no --estimate-error.
void add_estimate_flags(CLI::App& command, ErrorEstimate& estimate, bool sweep);
// Throws BadInput for a --target-error that is not a number > 0, or (on a sweep) one given
// without --estimate-error, which would not be used.
void check_estimate_flags(const CLI::App& command, const ErrorEstimate& estimate, bool sweep);

}  // namespace pb::app
