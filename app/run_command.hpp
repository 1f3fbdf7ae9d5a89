#pragma once
// `poundbench run`: one case, one solver -> Pi1 and the event counts, as a short summary
// or one JSON object, and optionally the time history as CSV.

#include <string>

#include <CLI/CLI.hpp>

#include "frontend/case_flags.hpp"
#include "frontend/solver_flags.hpp"

namespace pb::app {

struct RunFlags {
  CaseFlags case_flags;
  SolverFlags solver_flags;
  bool json = false;
  std::string history;
  int samples = 2000;
  double k_contact = 0.0;  // --k-contact (frontend/contact_stiffness.hpp)
  // A fixed-step run's error estimate, always made (a companion solve at 2h); --target-error.
  ErrorEstimate estimate{.on = true};
};

CLI::App* add_run_command(CLI::App& app, RunFlags& flags);
// Exit code: 0 when the solver reached t_end, 1 when it did not (the result is printed).
int run_command(const CLI::App& command, RunFlags flags);

}  // namespace pb::app
