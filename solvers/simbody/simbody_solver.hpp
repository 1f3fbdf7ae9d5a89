#pragma once
// Simbody (Debian's libsimbody 3.7) as a pounding solver, the last of the engines Gazebo
// offers. Each building is a MobilizedBody::Slider along x with a MobilityLinearSpring and a
// MobilityLinearDamper, the ground load a Force::Custom (model.hpp). Two kinds of contact:
//
//   rigid      (plus-faithful, pgs-faithful, default) conditional constraints, HardStopLower
//              for the wall and PointPlaneFrictionlessContact between bodies, stepped by
//              SemiExplicitEulerTimeStepper: impacts by Poisson's law at the step's start
//              (compression, then expansion: what the reference applies to simultaneous
//              impacts, which no other time-stepper here does), then the step's forces with
//              the contacts held; semi-explicit Euler with explicit springs.
//   compliant  (hunt-crossley) HuntCrossleyForce elements in a GeneralContactSubsystem,
//              integrated by Simbody's error-controlled Runge-Kutta-Merson and reported on a
//              fine grid: not a time-stepper (no --steps).
//
// Every variant is built in the pulse's units (a_p = w_p = m0 = 1). The run around the steps
// is the shell every time-stepper shares, kit/fixed_step.hpp. Debian's build prints a
// trace of every step on stdout: quiet_stdout.hpp keeps it off, per thread.

#include <string>
#include <vector>

#include "kit/solver.hpp"

namespace pb::simbody {

Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);
std::vector<VariantInfo> variant_list();
// Its one contact element, Hunt-Crossley, is of the Hertz family (SolverInfo::hertz_contact):
// --k-contact is in N/m^1.5 whatever the variant (only hunt-crossley uses it).
inline bool hertz_contact(const Settings&) { return true; }

}  // namespace pb::simbody
