#pragma once
// The two integrators of the compliant solver (compliant.hpp), each a whole run.

#include "kit/contact_elements/contact_law.hpp"
#include "kit/solver.hpp"

namespace pb::compliant {

// SUNDIALS CVODE, BDF or Adams (cvode_run.cpp).
Result run_cvode(const System& sys, const Settings& set, Model model, double K, bool adams);
// Average-acceleration Newmark in the fixed-step shell (newmark.cpp).
Result run_newmark(const System& sys, const Settings& set, Model model, double K);

}  // namespace pb::compliant
