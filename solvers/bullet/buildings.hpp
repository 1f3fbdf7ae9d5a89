#pragma once
// Bullet on the buildings scene (cases/buildings.hpp), as it runs the single oscillators
// (engine.hpp, README.md "Buildings"):
//
//   bodies    one btRigidBody per floor (make_body: linear factor (1,0,0), no rotation), at
//             x = u (ground-relative), all at the origin at rest: no joint, Bullet's linear
//             factor keeps them on the x axis.
//   forces    Bullet has no spring between two rigid bodies but its constraint-based
//             btGeneric6DofSpring2Constraint, which it steps as a soft constraint row, not
//             a force: the storeys' -K u, the buildings' full -C v (Rayleigh or modal) and
//             the ground load -m a_g(t_k) are applied at the start of each step
//             (applyCentralForce), so Bullet's semi-implicit Euler takes them explicitly.
//   contacts  per floor pair (BuildingModel::contacts) a btPersistentManifold (A the right
//             building's floor, B the left's) holding one point while the variant's rule
//             takes the contact, exactly as the single oscillators' (engine.cpp), and every
//             manifold with a point goes to the variant's solveGroup.
//
// Every variant of kVariants runs. Bullet computes in single precision: positions carry u
// with ~6e-8 relative resolution. Peaks at every step end (FloorPeaks); an impact is a point
// made for a contact that had none the step before, approaching faster than kRestitutionFloor
// a_p / w_p, as moreau-jean counts them.

#include <string_view>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/solver.hpp"

namespace pb::bullet {

// The settings the buildings solve reads (SolverInfo::buildings_settings), besides the variant.
inline constexpr std::string_view kBuildingsSettings[] = {"steps", "wh", "h_s", "steps_per_sample", "gamma", "step_cap",
                                                          "time_limit"};

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings);

}  // namespace pb::bullet
