#pragma once
// An example of a new solver (examples/new_solver/README.md): symplectic Euler with Newton
// impacts on the predicted contacts, in the fixed-step shell every time-stepper shares.

#include <string>
#include <vector>

#include "cases/system.hpp"
#include "solvers/solver.hpp"

namespace pb::symplectic_euler {

Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);
std::vector<VariantInfo> variant_list();

}  // namespace pb::symplectic_euler
