#pragma once
// What an element restitutes with nothing else acting: one body, no spring, no dashpot, no
// ground load, approaching the wall at unit speed through its element, solved by the solver
// itself (CVODE at rtol 1e-12, the contact's onset and end at its root functions) and read
// as the solver reads every isolated impact (Result::restitution_low). The element's own
// restitution, against which a pounding case's (where the bodies' springs and the pulse act
// during the contact too) shows the model's error. solvers/compliant/restitution_table_main.cpp writes it
// for every element and eps (reports/restitution.csv, README's table).

#include <string_view>

#include "kit/solver.hpp"

namespace pb::compliant {

// The free impact's Result for the element `variant` (a compliant variant name) at eps, with
// stiffness Pi term K (the body's mass and the unit of length and time are 1; the impact's
// restitution does not depend on K or on the speed: every element's isolated impact is
// scale-free, contact_law.hpp).
Result free_impact(std::string_view variant, double eps, double K = 1.0);

}  // namespace pb::compliant
