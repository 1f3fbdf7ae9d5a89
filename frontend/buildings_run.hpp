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
#include "rows/buildings_rows.hpp"

namespace pb::app {

// The solver's registry row, if it solves the buildings scene; else throws BadInput, one line
// ("--solver: X does not solve the buildings scene (these do: ...)"), as for a setting given
// that its buildings solve does not read (SolverInfo::buildings_settings).
const SolverInfo& check_buildings_solver(const SolverFlags& flags, const GivenSolverFlag& given);

// --k-contact K (N/m; N/m^1.5 for a Hertz-type element) on a buildings point: the Pi term
// --stiffness of the chosen solver's element (cases/buildings.hpp, contact_element_stiffness),
// into flags.settings. Throws BadInput, one line: with --stiffness, a k not finite and > 0,
// a solver whose buildings solve has no contact element.
void apply_buildings_k_contact(const BuildingScene& scene, SolverFlags& flags, double k, bool stiffness_given);

struct BuildingsRun {
  ChosenCase chosen;  // its `building` is the point solved
  const SolverInfo* solver = nullptr;
  BuildingsPoint point;  // the solver's result, its time, and the reference's no-contact response
};

BuildingsRun run_buildings(const ChosenCase& chosen, const SolverInfo& solver, const Settings& settings);

// The object of `run --json`: floor_peak_m, drift_peak_m (per building, floor 1 first), the
// same without contact (floor_peak_no_contact_m, drift_peak_no_contact_m), contacts (each with
// its impacts and the gap that avoids pounding at its floor level with the rules' gaps,
// separation_m ... separation_ddc_m), the Pi terms of a case in Pi terms, status, message,
// events, energy_error, seconds, cpu_seconds, and what names the point.
nlohmann::ordered_json buildings_json(const BuildingsRun& run);
// The summary `run` prints without --json.
void print_buildings_summary(std::ostream& out, const BuildingsRun& run);

}  // namespace pb::app
