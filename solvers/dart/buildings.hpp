#pragma once
// DART on the buildings scene (cases/buildings.hpp; solvers/dart/README.md, "Buildings"). The
// single oscillators' three variants, each on the floors:
//
//   dantzig-faithful, pgs-faithful   a skeleton per floor, its one body on a PrismaticJoint along
//             x from the world; the storeys' springs and the building's damping C (Rayleigh or
//             modal, a full matrix per building in general) applied as the joints' forces
//             -(K u)_i - (C v)_i - m_i a_g(t_k) at the step's start; a GapConstraint per floor
//             contact armed by the activation rule g + gamma h g' <= 0, restitution eps: ODE's
//             faithful scheme (semi-implicit Euler, explicit springs, Newton's law on the
//             active contacts), first order.
//   default   what a DART user builds: a skeleton per building, a chain of PrismaticJoints (floor
//             i on floor i - 1), each joint's own spring k_i and damper (the storey's: a1 k_i of
//             Rayleigh's C) integrated implicitly by DART; the rest of C (a0 M, or all of a modal
//             C) and the ground load as external forces; a unit box per floor in contact,
//             collided by FCL, restitution eps on each shape, DART's defaults; at the suite's
//             normalisation (a_p = w_p = 1, masses over floor 1's).
//
// Peaks at every step end (FloorPeaks); an impact is a contact that enters the step's contact
// set (armed, or found by FCL) approaching faster than kRestitutionFloor a_p / w_p at the
// step's start, as moreau-jean counts them.

#include <string_view>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/solver.hpp"

namespace pb::dart {

// The settings the buildings solve reads (SolverInfo::buildings_settings), besides the variant.
inline constexpr std::string_view kBuildingsSettings[] = {"steps", "wh", "h_s", "steps_per_sample", "gamma", "step_cap",
                                                          "time_limit"};

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings);

}  // namespace pb::dart
