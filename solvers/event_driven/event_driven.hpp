#pragma once
// The event-driven reference solver: exact between events, Poisson impacts, persistent
// contact and detachment. The derivation is in solvers/event_driven/DERIVATION.md.

#include <string>

#include "solvers/solver.hpp"

namespace pb::event_driven {

Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);

// Pi1 of body 0 with every contact removed: a damped oscillator under the pulse, exact.
double no_contact_pi1(const System& system);

}  // namespace pb::event_driven
