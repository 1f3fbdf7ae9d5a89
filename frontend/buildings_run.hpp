#pragma once
// A point of a buildings case set through `run` and poundbench.run (cases/buildings_set.hpp):
// which solver may solve it, the solve, and what is reported: a short summary, and the object
// `run --json` prints and poundbench.run returns (docs/cli.md, "The buildings scene").

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "cases/buildings_set.hpp"
#include "frontend/case_flags.hpp"
#include "frontend/solver_flags.hpp"
#include "solvers/buildings_reference/reference.hpp"

namespace pb::app {

// The settings of kit/settings_fields.hpp that the buildings reference reads: what a
// buildings run may be given besides --solver.
inline constexpr std::string_view kBuildingsSettings[] = {"tol_scale", "step_cap", "time_limit"};

// Throws BadInput, one line, for a solver other than the reference ("solver X does not solve
// the buildings scene (yet): ...") and for a setting that the reference does not read.
void check_buildings_solver(const SolverFlags& flags, const GivenSolverFlag& given);

struct BuildingsRun {
  ChosenCase chosen;  // its `building` is the point solved
  buildings::BuildingsResult result;
  double seconds = 0.0, cpu_seconds = 0.0;  // the solve's wall and CPU time (this thread's)
};

BuildingsRun run_buildings(const ChosenCase& chosen, const Settings& settings);

// The object of `run --json`: floor_peak_m, drift_peak_m (per building, floor 1 first),
// contacts, the Pi terms of a case in Pi terms, status, message, events, energy_error,
// seconds, cpu_seconds, and what names the point.
nlohmann::ordered_json buildings_json(const BuildingsRun& run);
// The summary `run` prints without --json.
void print_buildings_summary(std::ostream& out, const BuildingsRun& run);

}  // namespace pb::app
