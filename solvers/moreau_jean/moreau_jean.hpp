#pragma once
// The Moreau-Jean time-stepper: a theta-method on velocities with Newton's impact law on
// the contacts that a look-ahead predicts closed. The scheme, its derivation and its
// choices are in solvers/moreau_jean/README.md; the step loops are in stepper.hpp
// (fixed sizes: wall, pair, row3, one body alone) and dynamic.hpp (any row of bodies).
// A run starts from System::u_start, v_start (rest when they are empty).

#include <string>
#include <string_view>
#include <vector>

#include "kit/fixed_step.hpp"
#include "kit/solver.hpp"

namespace pb::moreau_jean {

// Variants: how a step's ground load is formed (README, "Ground load"); variant_list says how.
inline constexpr std::string_view kStepMean = "step-mean";  // the default
inline constexpr std::string_view kEndSamples = "end-samples";

Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);
std::vector<VariantInfo> variant_list();

// The any-size path forced on a system that solve() would give to a fixed-size one, so that
// tests and benchmarks can compare the two paths on the same runs.
Result solve_dynamic(const System& system, const Settings& settings);

}  // namespace pb::moreau_jean
