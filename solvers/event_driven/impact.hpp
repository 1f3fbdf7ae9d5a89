#pragma once
// Poisson's impact law for frictionless, centric contacts of bodies in a row, through the
// compression and expansion LCPs of Pfeiffer & Glocker (the paper's eqs 2 and 3, with the
// expansion complementarity on the extra impulse Lambda_P = Lambda_E - eps Lambda_C, as
// cases.md prescribes):
//
//   compression: gd_C = G Lambda_C + gd_A,               0 <= gd_C  perp  Lambda_C >= 0
//   expansion:   gd_E = G Lambda_P + eps G Lambda_C + gd_C, 0 <= gd_E perp Lambda_P >= 0
//
// with G = W^T M^-1 W over the contacts of the impact and gd the normal relative
// velocities. For one contact this is gd_E = -eps gd_A, which is also Newton's law.

#include <span>
#include <vector>

#include "cases/system.hpp"

namespace pb::event_driven {

struct ImpactOutcome {
  std::vector<double> impulse;   // total impulse Lambda_C + Lambda_E per contact of the set
  std::vector<double> gap_rate;  // gd_E per contact of the set
};

// Applies the impact on the contacts `set` (indices of System contacts) to the body
// velocities v (left to right), in place. Throws std::invalid_argument beyond two
// contacts (the scenes of the case set need no more).
ImpactOutcome poisson_impact(const System& s, std::span<const int> set, std::span<double> v, double eps);

// Normal relative velocity of contact j: d/dt (delta + u_right - u_left).
double gap_rate(const System& s, int j, std::span<const double> v);

}  // namespace pb::event_driven
