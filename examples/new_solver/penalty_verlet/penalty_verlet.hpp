#pragma once
// The compliant example of a new solver (examples/new_solver/README.md): velocity Verlet with a
// Kelvin-Voigt contact element (kit/contact_elements) acting while a gap is closed, in the
// fixed-step shell every time-stepper shares. Its contacts last over steps: it keeps them as
// whole contacts (kit/whole_contacts.hpp), so that an impact is counted once per contact and
// its restitution measured over the whole contact.

#include <string>
#include <vector>

#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb::penalty_verlet {

Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);
std::vector<VariantInfo> variant_list();

}  // namespace pb::penalty_verlet
