#pragma once
// The StepMonitor of the fixed-size Moreau-Jean loop (stepper.hpp): the same measurements
// (kit/monitor.hpp says what they are) on the loop's own fixed-size vectors, inlined
// into its step, with the energy balance kept per body.
//
// Why a second monitor: the loop's step costs 68 instructions on pair and 120 on row3
// (callgrind), and the general StepMonitor called from it 221 and 278 more (3.1x and 2.7x
// the time). Inlined on the loop's vectors, with StepMonitor's arithmetic in StepMonitor's
// order, it still cost 52 and 87 more (1.6x and 1.8x the time): summing each step's
// energy, load and damping over the bodies before combining them takes three horizontal
// sums of SSE2 pairs a step, with their moves. So the balance is kept per body instead,
//
//   b_i += (E_i,k+1 - E_i,k) + (c_i / h) du_i^2 + abar m_i du_i,   balance = sum_i b_i,
//
// every body's terms formed at once in one SSE2 register (two bodies to a register), and
// one horizontal sum a step, of the b_i. Measured on pair and row3: 1.2x and 1.3x the time of
// the unmonitored loop (solvers/moreau_jean/moreau_jean_bench.cpp); since, with the loop itself faster,
// 1.26x and 1.51-1.55x (126 and 202 instructions a step on row3, callgrind). The loop's state
// and the monitor's running values do not fit in the sixteen XMM registers: what is spilled
// is stored and loaded every step, so the monitor now carries no copy of what the loop has.
// The step's displacement du comes from the loop, formed before its new q overwrites the old
// (it had been copied through the stack), and the gap rates at the step's start are the
// loop's st.rate, read before it is updated (the monitor had kept the last step's own). Both
// are the same numbers: du is the same difference, and W^T v differs from v_r - v_l (finite
// velocities) at most in the sign of a zero, where the one use of those rates, an impact's
// approach below -floor_, is not. 1.27x and 1.44-1.47x (130 and 199 instructions a step on
// row3).
// Tried on row3 and slower, each by instructions and time: the stepper's gap rates at the
// step's end passed in instead of recomputed; the odd body padded into a zero lane;
// per-contact maxima of |g'| (tried twice), or their maximum in scalars; the step before's
// impulses from the loop (no change); the excess and the largest |g'| in one register;
// each body's energy change from (v - v0)(v + v0) instead of a carried energy; the whole
// monitor run over blocks of 64 steps after the loop, two steps to a register (242
// instructions a step: storing the states and reading them back cost more than the spills).
//
// The same quantities, to round-off. The sum of a step's terms is taken body by body
// instead of term by term, and c / h is rounded once per run: each step's increment differs
// from StepMonitor's by a few roundings of its terms, at most (4 NB + 4) 2^-53 E_max, with
// E_max the largest energy of the run; over n steps, the balance and so the energy excess by
// at most (4 NB + 4) n 2^-53 E_max, 1.2e-11 of E_max at 8 192 steps on row3, against the
// stress check's tolerance of 1e-6 of the energy scale (measured: solvers/moreau_jean/moreau_jean_test.cpp).
// The restitutions, the isolated impacts and the largest gap rate are StepMonitor's to the
// last bit (the same operations on the same numbers).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb::moreau_jean {

template <int NB, int NC>
class FixedStepMonitor {
 public:
  using VecB = Eigen::Matrix<double, NB, 1>;
  using VecC = Eigen::Matrix<double, NC, 1>;
  // Bodies are taken two to an SSE2 register (kPaired of them) and an odd last one alone:
  // Eigen does not vectorise a 3-vector (row3 took 94 instructions a step more than the
  // unmonitored loop as a Vector3d, 18 ns a step padded to a Vector4d through memory).
  static constexpr int kPaired = NB / 2 * 2;
  static constexpr bool kOdd = NB % 2 == 1;
  using Pairs = Eigen::Matrix<double, kPaired, 1>;

  // What a step changes. The loop keeps a copy in its own locals (stepper.hpp, advance),
  // where the compiler holds it in registers; left in the monitor it was stored and reloaded
  // at every step.
  struct Running {
    Pairs energy;           // E_i at the start of the step, per body (the paired ones)
    Pairs balance;          // b_i: E_i + D_i - E_i,0 - W_i, per body (the paired ones)
    double last_energy = 0.0, last_balance = 0.0;  // the same, for an odd last body
    unsigned pushed = 0;    // impulses of the step before (bit j: contact j)
    double excess = 0.0;    // the largest balance (sum of the b_i) so far
    double fastest = 0.0;   // largest |g'| so far
    long isolated = 0;
    double e_low = std::numeric_limits<double>::quiet_NaN(), e_high = std::numeric_limits<double>::quiet_NaN();
  };

  // Starts from System::u_start, v_start (empty: rest), as StepMonitor does; h is the step.
  FixedStepMonitor(const System& s, double h);

  // One step under the step-mean ground acceleration abar that moved the displacements by
  // du to the state (u, v), from gap rates rate0 (the loop's, W^T v at the step's start);
  // bit j of `pushed`: contact j carried a positive impulse.
  [[gnu::always_inline]] inline void step(Running& r, double abar, const VecB& du, const VecB& u, const VecB& v,
                                          const VecC& rate0, unsigned pushed) const;
  // The same from the states at the step's two ends, (u0, v0) and (u, v).
  void step(double abar, const VecB& u0, const VecB& v0, const VecB& u, const VecB& v, unsigned pushed) {
    VecC rate0;
    for (int j = 0; j < NC; ++j) rate0(j) = rate(j, v0);
    step(running_, abar, (u - u0).eval(), u, v, rate0, pushed);
  }
  Running& running() { return running_; }

  // Writes energy_excess, isolated_impacts, the restitution range and gap_rate_max into r.
  void finish(Result& r) const {
    r.energy_excess = running_.excess / energy_scale_;
    r.isolated_impacts = running_.isolated;
    r.restitution_low = running_.e_low;
    r.restitution_high = running_.e_high;
    r.gap_rate_max = running_.fastest;
  }

 private:
  // Contact j joins bodies j - 1 + kShift and j + kShift; with a wall (NB == NC: a row has
  // as many contacts as bodies exactly when it has a wall) contact 0's left is the wall.
  static constexpr int kShift = NB - NC;
  [[gnu::always_inline]] static double rate(int j, const VecB& v) {
    const int l = j - 1 + kShift;
    return v(j + kShift) - (l < 0 ? 0.0 : v(l < 0 ? 0 : l));  // System::gap_rate
  }
  // Body i's terms (the paired bodies' in one register, or the odd last one's): its energy,
  // and the balance's increment over a step that ends in (u, v) from energy e0 and moves it
  // by du.
  template <class X>
  [[gnu::always_inline]] static X energy(const X& half_m, const X& half_k, const X& u, const X& v) {
    return half_m * v * v + half_k * u * u;
  }
  template <class X>
  [[gnu::always_inline]] static X increment(const X& e, const X& e0, const X& m, const X& c_over_h, const X& du,
                                            double abar) {
    return (e - e0) + du * (c_over_h * du + abar * m);
  }

  // Per body: m, m / 2, k / 2, c / h; the paired ones as arrays, an odd last one apart.
  Eigen::Array<double, kPaired, 1> m_, half_m_, half_k_, c_over_h_;
  double last_m_ = 0.0, last_half_m_ = 0.0, last_half_k_ = 0.0, last_c_over_h_ = 0.0;
  double floor_ = 0.0;                   // kRestitutionFloor a_p / w_p
  double energy_scale_ = 1.0;
  Running running_;
};

template <int NB, int NC>
FixedStepMonitor<NB, NC>::FixedStepMonitor(const System& s, double h)
    : floor_(kRestitutionFloor * s.a_p / s.pulse.w), energy_scale_(s.energy_scale()) {
  if (s.n_bodies() != NB || s.n_contacts() != NC)
    throw std::logic_error("FixedStepMonitor: the System's size is not the monitor's");
  VecB u = VecB::Zero(), v = VecB::Zero();
  for (int i = 0; i < NB; ++i) {
    const auto b = static_cast<std::size_t>(i);
    const double m = s.bodies[b].m, half_m = 0.5 * m, half_k = 0.5 * s.bodies[b].k, c_over_h = s.bodies[b].c / h;
    if (i < kPaired) {
      m_(i) = m;
      half_m_(i) = half_m;
      half_k_(i) = half_k;
      c_over_h_(i) = c_over_h;
    } else {
      last_m_ = m;
      last_half_m_ = half_m;
      last_half_k_ = half_k;
      last_c_over_h_ = c_over_h;
    }
    if (s.u_start.size() == static_cast<std::size_t>(NB)) u(i) = s.u_start[b];
    if (s.v_start.size() == static_cast<std::size_t>(NB)) v(i) = s.v_start[b];
  }
  if constexpr (kPaired > 0) {
    const auto up = u.template head<kPaired>().array(), vp = v.template head<kPaired>().array();
    running_.energy = energy<Eigen::Array<double, kPaired, 1>>(half_m_, half_k_, up, vp).matrix();
    running_.balance.setZero();
  }
  if constexpr (kOdd) running_.last_energy = energy(last_half_m_, last_half_k_, u(NB - 1), v(NB - 1));
  for (int j = 0; j < NC; ++j) running_.fastest = std::max(running_.fastest, std::abs(rate(j, v)));
}

template <int NB, int NC>
void FixedStepMonitor<NB, NC>::step(Running& r, double abar, const VecB& du, const VecB& u, const VecB& v,
                                    const VecC& rate0, unsigned pushed) const {
  double balance = 0.0;
  if constexpr (kPaired > 0) {
    using A = Eigen::Array<double, kPaired, 1>;
    const A up = u.template head<kPaired>().array(), vp = v.template head<kPaired>().array();
    const A e = energy<A>(half_m_, half_k_, up, vp);
    r.balance += increment<A>(e, r.energy.array(), m_, c_over_h_, du.template head<kPaired>().array(), abar).matrix();
    r.energy = e.matrix();
    balance = r.balance(0);
    for (int i = 1; i < kPaired; ++i) balance += r.balance(i);
  }
  if constexpr (kOdd) {
    const double e = energy(last_half_m_, last_half_k_, u(NB - 1), v(NB - 1));
    r.last_balance += increment(e, r.last_energy, last_m_, last_c_over_h_, du(NB - 1), abar);
    r.last_energy = e;
    balance = kPaired > 0 ? balance + r.last_balance : r.last_balance;
  }
  r.excess = std::max(r.excess, balance);

  // Isolated impacts: one contact pushing, which did not push in the step before. Rare, so
  // tested once for the step before looking at the contacts. Exactly one bit set is tested
  // by hand: std::popcount is a call into libgcc without -mpopcnt (21 instructions a step).
  const bool starts_alone = (pushed & ~r.pushed) != 0 && (pushed & (pushed - 1)) == 0;
  VecC now;
  for (int j = 0; j < NC; ++j) now(j) = rate(j, v);
  if constexpr (NC > 0) r.fastest = std::max(r.fastest, now.cwiseAbs().maxCoeff());  // one max on the carried value
  if (starts_alone) [[unlikely]] {
    for (int j = 0; j < NC; ++j) {
      const double before = rate0(j);
      if ((pushed >> j & 1u) && before < -floor_) {
        const double e_j = -now(j) / before;
        ++r.isolated;
        r.e_low = r.isolated == 1 ? e_j : std::min(r.e_low, e_j);
        r.e_high = r.isolated == 1 ? e_j : std::max(r.e_high, e_j);
      }
    }
  }
  r.pushed = pushed;
}

}  // namespace pb::moreau_jean
