#pragma once
// The flags that pick a solver and fill its Settings, shared by `run` and `spectrum`.

#include <string>

#include <CLI/CLI.hpp>

#include "solvers/solver.hpp"

namespace pb::app {

struct SolverFlags {
  std::string solver{reference_solver().name};  // the default: the reference
  Settings settings;
};

void add_solver_flags(CLI::App& command, SolverFlags& flags);

// The named solver, after SolverInfo::check accepted the settings; throws BadInput.
const SolverInfo& checked_solver(const SolverFlags& flags);

// "field: reason" from a check() with the field turned into its flag, e.g. "--tol-scale: ...".
std::string as_flag_message(const std::string& field_reason);

}  // namespace pb::app
