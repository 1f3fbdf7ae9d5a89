#pragma once
// MuJoCo on the buildings scene (cases/buildings.hpp), as it runs the single oscillators
// (model.hpp, README.md "Buildings"):
//
//   bodies    one body per floor on a slide joint along x to the world, qpos = u
//             (ground-relative); a sphere per floor, the buildings kRadius + delta / 2 apart
//             on each side, so that MuJoCo's distance between floor j of two neighbours is the
//             gap delta + u_R - u_L; an explicit condim-1 pair per floor contact.
//   storeys   MuJoCo's own elements: a fixed tendon per storey, length u_i - u_{i-1} (floor 1:
//             u_1), its stiffness k_i. Rayleigh damping C = a0 M + a1 K exactly: the tendon's
//             damping a1 k_i and the floor's joint damping a0 m_i (Euler treats the joint's
//             implicitly, the implicit integrator both). Modal damping is a full matrix per
//             building that no element carries: -C v into qfrc_applied at every evaluation.
//   load      -m a_g(t) into qfrc_applied from mjcb_control at every evaluation (RK4: its
//             four stages), as the single oscillators'.
//   contacts  MuJoCo's soft contacts, calibrated to eps with time constant --contact-steps
//             steps (faithful) or its defaults (default): contact.hpp.
//   units     faithful: the pulse's (length a_p / w_p^2, time 1 / w_p) and floor 1 of the left
//             building's mass; default: the case's own (SI).
//
// Every variant of kVariants runs. Peaks at every step end (FloorPeaks); an impact is a contact
// MuJoCo reports with a positive force in a step when it had none in the step before,
// approaching faster than kRestitutionFloor a_p / w_p at the step's start.

#include <string_view>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/solver.hpp"

namespace pb::mujoco {

// The settings the buildings solve reads (SolverInfo::buildings_settings), besides the variant.
inline constexpr std::string_view kBuildingsSettings[] = {"steps",         "wh", "h_s",       "steps_per_sample",
                                                          "contact_steps", "step_cap", "time_limit"};

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings);

}  // namespace pb::mujoco
