#pragma once
// An example of a new solver (examples/new_solver/README.md): symplectic Euler with Newton
// impacts on the predicted contacts, in the fixed-step shell every time-stepper shares.

#include <array>
#include <string>
#include <vector>

#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb::symplectic_euler {

// Its own setting (SolverInfo::own_settings): `--passes K`, the passes of Newton's law over the
// contacts in a step. One pass is exact for an isolated impact; where contacts share a body
// (row3, a chain) each pass brings the impulses nearer the simultaneous impact's.
inline constexpr std::array<OwnSetting, 1> kOwnSettings = {{
    {"passes", "Symplectic Euler: passes of Newton's law over the contacts per step (default 1)", 1.0},
}};

Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);
std::vector<VariantInfo> variant_list();

}  // namespace pb::symplectic_euler
