#pragma once
// What every time-stepper measures for the stress checks, from the states at the ends of
// each step: the energy balance and the restitution of isolated impacts (Result).
//
// The balance E + D - E0 - W uses, over a step of length h,
//   W += -h abar sum m_i (v_i + v_i') / 2     D += h sum c_i ((v_i + v_i') / 2)^2
// with abar the exact step mean of a_g. For the Moreau-Jean scheme with theta = 1/2 this is
// the scheme's own discrete balance, so the excess is round-off; for any other scheme it
// measures the energy the scheme makes or loses over and above the physics, to O(h^2)
// per unit time.
//
// Holds its buffers from construction on: observing a step allocates nothing.

#include <vector>

#include "cases/system.hpp"
#include "solvers/solver.hpp"

namespace pb {

class StepMonitor {
 public:
  explicit StepMonitor(const System& s);

  // One step of length h under the step-mean ground acceleration abar: the state at its
  // end (u, v, one value per body) and whether each contact carried a positive impulse in
  // it. The state at its start is the one of the previous call (or System's start).
  void step(double h, double abar, const double* u, const double* v, const char* pushed);

  // Writes energy_excess, isolated_impacts and the restitution range into r.
  void finish(Result& r) const;

 private:
  double rate(int j, const double* v) const;

  const System& s_;
  std::vector<double> v_, rate_;  // velocities and gap rates at the start of the step
  std::vector<char> pushed_;      // impulses of the step before
  double energy_ = 0.0;           // E at the start of the step
  double balance_ = 0.0;          // E + D - E0 - W
  double excess_ = 0.0;
  double floor_ = 0.0;  // kRestitutionFloor a_p / w_p
  long isolated_ = 0;
  double e_low_, e_high_;
};

}  // namespace pb
