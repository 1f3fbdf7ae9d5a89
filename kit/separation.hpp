#pragma once
// The gap that avoids pounding and the rules engineers use for it (cases/README.md,
// "Separation"): what the motion with every contact removed (the reference's free_motion)
// says, and what each building's own peak gives by ABS, SRSS and the double difference
// combination (DDC).

#include <string>
#include <vector>

#include "cases/buildings.hpp"
#include "cases/system.hpp"
#include "kit/buildings_result.hpp"
#include "kit/solver.hpp"

namespace pb {

// The motion of every body of a system with every contact removed (event_driven::free_motion):
// per body its peak |u_i|; per contact how far its bodies come towards each other,
// max(u_left - u_right) (a wall's u is 0), and how far apart, max(u_right - u_left). Lengths
// in the system's units; empty vectors where status is not ok (message says why).
struct FreeMotion {
  Status status = Status::ok;
  std::string message;
  std::vector<double> peak;              // per body
  std::vector<double> closing, opening;  // per contact
};

// The CQC correlation coefficient of two modes of damping ratios xi_a, xi_b and frequency
// ratio r = w_b / w_a (Der Kiureghian 1981): 1 for two identical modes, whatever the damping.
double cqc_rho(double xi_a, double xi_b, double r);

// The rules for one pair of neighbours from their own peaks u_a (left) and u_b (right):
// ABS = u_a + u_b, SRSS = sqrt(u_a^2 + u_b^2), DDC = sqrt(u_a^2 + u_b^2 - 2 rho u_a u_b).
struct SeparationRules {
  double abs = 0.0, srss = 0.0, ddc = 0.0;
};
SeparationRules separation_rules(double u_a, double u_b, double rho);

// The separation of a scene (every contact shares the one gap delta, so the gap that avoids
// pounding is the largest over its contacts, and so is each rule's): required, the largest
// closing of `given`; reversed, that under the load reversed: the largest closing of
// `reversed` where given (a yielding system, solved again), else the largest opening of
// `given` (a linear system's motion under -a_g is -u). The rules from each pair's peaks in
// `given`; a wall's side counts 0. Lengths in the system's units.
struct Separation {
  double required = 0.0, reversed = 0.0;
  SeparationRules rules;
};
Separation separation(const System& s, const FreeMotion& given, const FreeMotion* reversed);

// The separation of one floor level of a buildings scene (a contact of the scene; cases/README.md,
// "Separation"): the gap that avoids pounding there, required = max(u_left - u_right), and that
// under the load reversed, max(u_right - u_left) (linear buildings: the motion under -a_g is -u);
// the rules from the two floors' own no-contact peaks, DDC with rho of the two buildings' first
// modes (r = w_1,right / w_1,left, each mode's own damping ratio). Lengths in m.
struct FloorSeparation {
  int left = 0, right = 0, floor = 1;  // as FloorContact
  double required = 0.0, reversed = 0.0;
  double peak_left = 0.0, peak_right = 0.0;  // the floors' no-contact peaks
  double period_ratio = 0.0;                 // T_1,right / T_1,left
  double rho = 0.0;
  SeparationRules rules;
};
// Per contact of `free` (buildings::free_motion of the model's scene, status ok), in its order.
std::vector<FloorSeparation> floor_separations(const BuildingModel& model, const buildings::BuildingsResult& free);

}  // namespace pb
