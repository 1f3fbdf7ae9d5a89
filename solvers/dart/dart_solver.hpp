#pragma once
// DART (Debian's libdart 6.12) as a pounding solver, a physics engine Gazebo offers beside
// ODE and Bullet. Two models, each stepped by DART's World::step (semi-implicit Euler:
// v += h M^-1 F, constraint impulses, x += h v):
//
//   faithful  (dantzig-faithful, pgs-faithful) a skeleton per building, on a prismatic joint, a gap
//             constraint of this project's own per contact (gap_constraint.hpp) with ODE's
//             faithful contact row, explicit springs and dampers, the activation rule of
//             every faithful time-stepper (kit/fixed_step.hpp): ODE's dantzig-faithful
//             step for step (README: agreement to round-off).
//   default   what a new DART user builds: boxes collided by FCL, restitution on the shapes,
//             the joints' own springs and dampers, DART's defaults; at the suite's
//             normalisation (a_p = w_p = m0 = 1).
//
// The run around the steps (h, step count and cap, counts, monitor, history, limits) is the
// shell every time-stepper shares, kit/fixed_step.hpp. This header names no DART type:
// the folder's sources, which do, are compiled without NDEBUG, as Debian built DART (its
// classes' layouts depend on it: CMakeLists.txt).

#include <string>

#include "kit/solver.hpp"

namespace pb::dart {

Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);
std::vector<VariantInfo> variant_list();

}  // namespace pb::dart
