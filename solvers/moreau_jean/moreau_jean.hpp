#pragma once
// The Moreau-Jean time-stepper: a theta-method on velocities with Newton's impact law on
// the contacts that a look-ahead predicts closed. The scheme, its derivation and its
// choices are in solvers/moreau_jean/README.md; the step loop is in stepper.hpp.

#include <string>
#include <vector>

#include "solvers/solver.hpp"

namespace pb::moreau_jean {

inline constexpr int kDefaultSteps = 64;              // N when Settings::steps is 0
inline constexpr long kDefaultStepCap = 100'000'000;  // when Settings::step_cap is 0

Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);

// A start other than rest, for tests (free vibration, energy balance): one value per
// body, left to right. Not part of Settings: every case of the project starts at rest.
struct InitialState {
  std::vector<double> u, v;
};
Result solve_from(const System& system, const Settings& settings, const InitialState& start);

}  // namespace pb::moreau_jean
