#pragma once
// ODE on the buildings scene (cases/buildings.hpp), as it runs the single oscillators
// (ode_solver.hpp, README.md "Buildings"):
//
//   bodies    one dBody per floor on the x axis, position = u (ground-relative), no joint:
//             every force and contact row has only an x component, so y, z and rotation stay
//             exactly zero (checked at the end of the run, as for the single oscillators).
//   forces    ODE has no spring or damper between two bodies: the storeys' -K u, the
//             buildings' full -C v (Rayleigh or modal: a full matrix per building in general)
//             and the ground load -m a_g(t_k) are applied at the start of each step
//             (dBodyAddForce), so ODE's semi-implicit Euler takes them explicitly.
//   contacts  per floor pair (BuildingModel::contacts) a dContactJoint when the variant's rule
//             takes it (kit/fixed_step.hpp Activation), normal +x into the right building's
//             floor, depth max(0, -g), mu 0, bounce eps: the single oscillators' joint.
//
// Every variant of kVariants runs. Peaks at every step end (FloorPeaks); an impact is a contact
// that gets a joint it had not at the step before, approaching faster than kRestitutionFloor
// a_p / w_p, as moreau-jean counts them.

#include <string_view>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/solver.hpp"

namespace pb::ode {

// The settings the buildings solve reads (SolverInfo::buildings_settings), besides the variant.
inline constexpr std::string_view kBuildingsSettings[] = {"steps", "wh", "h_s", "steps_per_sample", "gamma", "step_cap",
                                                          "time_limit"};

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings);

}  // namespace pb::ode
