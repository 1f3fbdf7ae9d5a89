#pragma once
// What every time-stepper measures for the stress checks, from the states at the ends of
// each step: the energy balance, the restitution of isolated impacts and the fastest gap
// rate (Result).
//
// The balance E + D - E0 - W uses, over a step of length h that moves body i by du_i,
//   W += -abar sum m_i du_i     D += sum c_i du_i^2 / h
// with abar the exact step mean of a_g: the work of the step's mean load along the step's
// own displacement, and the damping force at the step's mean velocity du / h doing work
// along it. For the theta-method (Moreau-Jean) this is the scheme's own discrete balance:
// the excess is round-off at theta = 1/2 and not positive at theta = 1, except where the
// impact law itself adds energy. For a scheme that samples the load at the step's start
// (ODE, Bullet) it measures the energy that sampling makes, to O(h) per unit time.
//
// Holds its buffers from construction on: observing a step allocates nothing.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb {

// step() is inline, with the bodies' coefficients and the contacts' bodies copied into flat
// arrays of its own: out of line, reading them through System (s.bodies[i].m, s.gap_rate,
// s.energy), it cost 205 of Moreau-Jean's 291 instructions per step on pair (callgrind),
// 14.5 ns a step against 4.1 ns unmonitored. The fixed-size Moreau-Jean loop has a
// monitor of its own on its fixed-size vectors (solvers/moreau_jean/fixed_monitor.hpp): the
// same restitutions, isolated impacts and gap rate to the last bit, and the energy balance
// summed body by body, within the round-off bound that file states.
class StepMonitor {
 public:
  // Starts from System::u_start, v_start (empty: rest).
  explicit StepMonitor(const System& s);

  // One step of length h under the step-mean ground acceleration abar: the state at its
  // end (u, v, one value per body) and whether each contact carried a positive impulse in
  // it. The state at its start is the one of the previous call (or System's start).
  inline void step(double h, double abar, const double* u, const double* v, const char* pushed);

  // Writes energy_excess, isolated_impacts, the restitution range and gap_rate_max into r.
  void finish(Result& r) const;

 private:
  std::vector<double> m_, c_, k_;  // per body: mass, damping, stiffness
  std::vector<int> left_, right_;  // per contact: its bodies (left kWall: the wall)
  std::vector<double> u_;          // displacements at the start of the step
  std::vector<double> rate_;       // gap rates at the start of the step
  std::vector<char> pushed_;       // impulses of the step before
  double energy_ = 0.0;            // E at the start of the step
  double balance_ = 0.0;           // E + D - E0 - W
  double excess_ = 0.0;
  double fastest_ = 0.0;       // largest |g'| so far
  double floor_ = 0.0;         // kRestitutionFloor a_p / w_p
  double energy_scale_ = 1.0;  // System::energy_scale()
  long isolated_ = 0;
  double e_low_, e_high_;
};

void StepMonitor::step(double h, double abar, const double* u, const double* v, const char* pushed) {
  const std::size_t nb = u_.size(), nc = rate_.size();
  double load = 0.0, damping = 0.0, e = 0.0;
  for (std::size_t i = 0; i < nb; ++i) {
    const double du = u[i] - u_[i];
    load += m_[i] * du;
    damping += c_[i] * du * du;
    e += m_[i] * v[i] * v[i] + k_[i] * u[i] * u[i];  // System::energy, in its order
    u_[i] = u[i];
  }
  e = 0.5 * e;
  balance_ += e - energy_ + damping / h + abar * load;
  energy_ = e;
  excess_ = std::max(excess_, balance_);

  int pushing = 0;
  for (std::size_t j = 0; j < nc; ++j) pushing += pushed[j] ? 1 : 0;
  for (std::size_t j = 0; j < nc; ++j) {
    const double before = rate_[j];
    rate_[j] = v[right_[j]] - (left_[j] == kWall ? 0.0 : v[left_[j]]);  // System::gap_rate
    fastest_ = std::max(fastest_, std::abs(rate_[j]));
    if (pushing == 1 && pushed[j] && !pushed_[j] && before < -floor_) [[unlikely]] {
      const double e_j = -rate_[j] / before;
      ++isolated_;
      e_low_ = isolated_ == 1 ? e_j : std::min(e_low_, e_j);
      e_high_ = isolated_ == 1 ? e_j : std::max(e_high_, e_j);
    }
    pushed_[j] = pushed[j];
  }
}

}  // namespace pb
