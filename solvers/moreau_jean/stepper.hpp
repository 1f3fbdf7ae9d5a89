#pragma once
// The Moreau-Jean step loop for one scene shape: NB bodies and NC contacts known at
// compile time, so every vector and matrix of a step is a fixed-size Eigen type and the
// loop never allocates. This path serves wall, pair, row3 and one body alone; any other
// row of bodies takes the any-size path (dynamic.hpp), which does the same arithmetic.
// The scheme and every choice made here are derived and argued in
// solvers/moreau_jean/README.md; in short:
//
//   M_hat = M + h theta C + h^2 theta^2 K           (diagonal: bodies couple only by contact)
//   v_free  = v_k + M_hat^-1 h (-C v_k - K q_k - h theta K v_k - M 1 abar_k)
//   active  = { j : g_j,k + gamma h g'_j,k <= 0 }
//   0 <= W^T v_k+1 + eps W^T v_k  _|_  P >= 0  on the active contacts
//   v_k+1   = v_free + M_hat^-1 W P,   q_k+1 = q_k + h ((1 - theta) v_k + theta v_k+1)
//
// abar_k is the exact mean of a_g over [t_k, t_k+1] (zero past T_p), computed from a
// rotation recurrence for cos/sin(w_p t_k) resynchronised every kResync steps
// (loop_common.hpp).
//
// Layout follows "constant apart from changing": Scheme holds what a run never changes
// (built once, before the loop), State what a step changes, Tally what the result needs.
// What a step records (history) and whether a StepMonitor sees it are template flags, so
// the plain loop carries no test for either; the monitor is the fixed-size one
// (fixed_monitor.hpp), inlined into the step.
//
// Rejected alternatives: dynamic-size Eigen types for these scenes (heap temporaries, and
// size bookkeeping that outweighs arithmetic on 1 to 3 numbers: measured 2-5x slower, see
// README); a general LCP solver (the scenes need 1x1 and 2x2 only, solved exactly by
// lcp::solve1 / lcp::solve2); std::sin/std::cos every step (the main cost of a loaded step).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <vector>

#include "cases/system.hpp"
#include "kit/lcp/small.hpp"
#include "solvers/moreau_jean/loop_common.hpp"
#include "solvers/moreau_jean/fixed_monitor.hpp"

namespace pb::moreau_jean {

template <int NB, int NC>
struct Scheme {
  using VecB = Eigen::Matrix<double, NB, 1>;
  using VecC = Eigen::Matrix<double, NC, 1>;
  using MatCB = Eigen::Matrix<double, NC, NB>;
  using MatBC = Eigen::Matrix<double, NB, NC>;
  using MatCC = Eigen::Matrix<double, NC, NC>;

  double h = 0.0;
  double h_old = 0.0, h_new = 0.0;  // h (1 - theta), h theta
  double gamma_h = 0.0;             // gamma h
  double eps = 0.0;
  int ref = 0;
  double bound = 0.0;  // |u| above this is divergence
  // v_free = fv .* v + fq .* q + fa abar, and q_free = q + h (1 - theta) v + h theta v_free
  // expanded the same way, so that q_k+1 does not wait for v_k+1 (a shorter dependency
  // chain from one step to the next): q_free = qv .* v + qq .* q + qa abar.
  VecB fv, fq, fa;
  VecB qv, qq, qa;
  MatCB wt;        // W^T: gap rates are W^T v
  VecC delta;      // gaps at rest
  MatBC minv_w;    // M_hat^-1 W
  MatBC h_minv_w;  // h theta M_hat^-1 W: the impulse's share of q_k+1
  MatCC delassus;  // W^T M_hat^-1 W, the LCP matrix
  PulseLoad load;
};

template <int NB, int NC>
Scheme<NB, NC> make_scheme(const System& s, double h, double theta, double gamma,
                           LoadRule load = LoadRule::step_mean) {
  Scheme<NB, NC> sc;
  sc.h = h;
  sc.h_old = h * (1.0 - theta);
  sc.h_new = h * theta;
  sc.gamma_h = gamma * h;
  sc.eps = s.eps;
  sc.ref = s.ref;
  sc.bound = 1e6 * s.length_scale();
  typename Scheme<NB, NC>::VecB minv;
  for (int i = 0; i < NB; ++i) {
    const Body& b = s.bodies[static_cast<std::size_t>(i)];
    const double m_hat = b.m + h * theta * b.c + h * h * theta * theta * b.k;
    minv(i) = 1.0 / m_hat;
    sc.fv(i) = 1.0 - h * (b.c + h * theta * b.k) / m_hat;
    sc.fq(i) = -h * b.k / m_hat;
    sc.fa(i) = -h * b.m / m_hat;
    sc.qv(i) = sc.h_old + sc.h_new * sc.fv(i);
    sc.qq(i) = 1.0 + sc.h_new * sc.fq(i);
    sc.qa(i) = sc.h_new * sc.fa(i);
  }
  sc.wt.setZero();
  for (int j = 0; j < NC; ++j) {
    sc.wt(j, s.right(j)) = 1.0;
    if (s.left(j) != kWall) sc.wt(j, s.left(j)) = -1.0;
    sc.delta(j) = s.delta;
  }
  sc.minv_w = minv.asDiagonal() * sc.wt.transpose();
  sc.h_minv_w = sc.h_new * sc.minv_w;
  sc.delassus = sc.wt * sc.minv_w;
  sc.load = make_pulse_load(s.pulse, h, load, theta);
  return sc;
}

template <int NB, int NC>
struct State {
  typename Scheme<NB, NC>::VecB q, v;     // q is u, the displacement
  typename Scheme<NB, NC>::VecC g, rate;  // gaps and gap rates W^T v
  long k = 0;                             // steps taken: the state is at t_k = k h
  unsigned active = 0;                    // contacts in the index set of the last step (bit j)
  unsigned pushed = 0;                    // contacts with a positive impulse in the last step
  unsigned in_phase = 0;                  // contacts in a persistent-contact phase
};

template <int NB, int NC>
State<NB, NC> make_state(const Scheme<NB, NC>& sc, const typename Scheme<NB, NC>::VecB& q,
                         const typename Scheme<NB, NC>::VecB& v) {
  State<NB, NC> st;
  st.q = q;
  st.v = v;
  st.g = sc.delta + sc.wt * q;
  st.rate = sc.wt * v;
  return st;
}

// The step loop's helpers are forced inline: a call per step costs as much as the step.
#define PB_MJ_INLINE [[gnu::always_inline]] inline

template <int NB, int NC>
PB_MJ_INLINE void tally_state(const Scheme<NB, NC>& sc, const State<NB, NC>& st, Tally& t) {
  const double u = std::abs(st.q(sc.ref));
  if (u > t.u_max) {
    t.u_max = u;
    t.k_max = st.k;
  }
  if constexpr (NC > 0) t.g_min = std::min(t.g_min, st.g.minCoeff());
}

// One history row: t, u, v, g, lambda = P / h (History in kit/solver.hpp).
template <int NB, int NC>
void record(const Scheme<NB, NC>& sc, const State<NB, NC>& st, const typename Scheme<NB, NC>::VecC& impulse,
            std::vector<double>& out) {
  out.push_back(static_cast<double>(st.k) * sc.h);
  for (int i = 0; i < NB; ++i) out.push_back(st.q(i));
  for (int i = 0; i < NB; ++i) out.push_back(st.v(i));
  for (int j = 0; j < NC; ++j) out.push_back(st.g(j));
  for (int j = 0; j < NC; ++j) out.push_back(impulse(j) / sc.h);
}

// Impulses of the active contacts (bit j of mask), exact for 1 and 2 contacts.
template <int NC>
PB_MJ_INLINE Eigen::Matrix<double, NC, 1> contact_impulse(const Eigen::Matrix<double, NC, NC>& a,
                                                          const Eigen::Matrix<double, NC, 1>& q, unsigned mask) {
  Eigen::Matrix<double, NC, 1> p = Eigen::Matrix<double, NC, 1>::Zero();
  if constexpr (NC == 1) {
    p(0) = lcp::solve1(a(0, 0), q(0));
  } else if constexpr (NC == 2) {
    if (mask == 3u)
      p = lcp::solve2(a, q);
    else if (mask == 1u)
      p(0) = lcp::solve1(a(0, 0), q(0));
    else
      p(1) = lcp::solve1(a(1, 1), q(1));
  }
  return p;
}

// One step from st.k to st.k + 1 under the ground load abar (the step mean of a_g, or its
// end samples); work is the exact step mean, what the monitor counts as the ground's work.
// Returns false when the state is no longer finite or |u| passed the divergence bound.
template <int NB, int NC, bool kRecord, bool kMonitor>
PB_MJ_INLINE bool step(const Scheme<NB, NC>& sc, State<NB, NC>& st, Tally& t, double abar, double work,
                       std::vector<double>* history, const FixedStepMonitor<NB, NC>* monitor,
                       typename FixedStepMonitor<NB, NC>::Running* running) {
  using VecC = typename Scheme<NB, NC>::VecC;
  typename Scheme<NB, NC>::VecB v_new = sc.fv.cwiseProduct(st.v) + sc.fq.cwiseProduct(st.q) + sc.fa * abar;
  typename Scheme<NB, NC>::VecB q_new = sc.qv.cwiseProduct(st.v) + sc.qq.cwiseProduct(st.q) + sc.qa * abar;
  VecC impulse = VecC::Zero();
  unsigned mask = 0;
  if constexpr (NC > 0) {
    const VecC predicted = st.g + sc.gamma_h * st.rate;
    for (int j = 0; j < NC; ++j) mask |= (predicted(j) <= 0.0 ? 1u : 0u) << j;
    if (mask != 0u) {
      const VecC q = sc.wt * v_new + sc.eps * st.rate;
      impulse = contact_impulse<NC>(sc.delassus, q, mask);
      v_new += sc.minv_w * impulse;
      q_new += sc.h_minv_w * impulse;
      unsigned approaching = 0, pushing = 0;
      for (int j = 0; j < NC; ++j) {
        approaching |= (st.rate(j) < 0.0 ? 1u : 0u) << j;
        pushing |= (impulse(j) > 0.0 ? 1u : 0u) << j;
      }
      // Rare (a contact's first step): the time of the step's end, as the shell's (fixed_step.hpp).
      if (const unsigned hits = mask & ~st.active & approaching)
        for (int j = 0; j < NC; ++j)
          if (hits >> j & 1u) t.impact(static_cast<double>(st.k + 1) * sc.h, st.rate(j));
      const unsigned starts = pushing & st.pushed & ~st.in_phase;
      t.phases += std::popcount(starts);
      st.in_phase = (st.in_phase | starts) & pushing;
      st.pushed = pushing;
    } else {
      st.pushed = 0;
      st.in_phase = 0;
    }
    st.active = mask;
  }
  [[maybe_unused]] typename Scheme<NB, NC>::VecB du;  // the monitor's
  if constexpr (kMonitor) du = q_new - st.q;
  st.q = q_new;
  st.v = v_new;
  ++st.k;
  // Before the divergence test: a diverging run's energy excess shows the growth. Before the
  // new gap rates: the monitor takes the step's first ones from st.rate.
  if constexpr (kMonitor) monitor->step(*running, work, du, st.q, st.v, st.rate, st.pushed);
  if constexpr (NC > 0) {
    st.g = sc.delta + sc.wt * st.q;
    st.rate = sc.wt * st.v;
  }
  if (!(st.q.array().abs() <= sc.bound).all()) return false;
  tally_state(sc, st, t);
  if constexpr (kRecord) record(sc, st, impulse, *history);
  return true;
}

// Steps until st.k == k_end. Returns false if the run blew up (st is left at the bad step).
// history (kRecord) must have room reserved, monitor (kMonitor) must be given: nothing here
// allocates.
template <int NB, int NC, bool kRecord, bool kMonitor = false>
bool advance(const Scheme<NB, NC>& sc, State<NB, NC>& state, Tally& tally, long k_end, std::vector<double>* history,
             FixedStepMonitor<NB, NC>* monitor = nullptr) {
  // Work on local copies: the compiler must assume that a store through one reference may
  // change a double behind another, and would reload the state from memory every step.
  // The monitor's running values too (FixedStepMonitor::Running).
  State<NB, NC> st = state;
  Tally t = tally;
  typename FixedStepMonitor<NB, NC>::Running running;
  if constexpr (kMonitor) running = monitor->running();
  const bool ok = drive(sc.load, st.k, k_end, [&](double abar, double work) __attribute__((always_inline)) {
    return step<NB, NC, kRecord, kMonitor>(sc, st, t, abar, work, history, monitor, &running);
  });
  state = st;
  tally = t;
  if constexpr (kMonitor) monitor->running() = running;
  return ok;
}

#undef PB_MJ_INLINE

}  // namespace pb::moreau_jean
