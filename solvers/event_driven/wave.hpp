#pragma once
// Closed-form motion between two events.
//
// Between events every quantity the reference tracks (a body's displacement, a gap, a
// contact force) is a linear combination of a constant, a sinusoid at the pulse frequency
// and at most two damped sinusoids (one per moving cluster of bodies a gap joins):
//
//   f(t) = f0 + [P(t) - P(t0)] + sum_m [D_m(t - t0) - D_m(0)]
//   P(t)    = ps sin(w t) + pc cos(w t)                       (absolute time)
//   D_m(s)  = exp(-sigma s) (a cos(omega s) + b sin(omega s))
//   R_m(s)  = Re(r G_m(s)),  G_m(s) = (exp(i w s) - exp(z s)) / (i w - z),  z = -sigma + i omega
//
// R_m is the forced response from rest of a mode driven near its resonance (|i w - z| small
// against w). There P and D_m, each of size 1 / |i w - z|, would cancel to leave a motion
// of size s (exactly s sin, s cos at an undamped resonance): R_m keeps that difference in
// a form that stays exact at, near and away from resonance (DERIVATION.md §1).
//
// The value is stored as f0 plus increments, and the increments are evaluated with
// half-angle and expm1 forms, so a gap that starts at exactly zero stays resolved far
// below the round-off of the displacements it is made of (chattering impacts depend on it).
//
// Why not a general ODE integrator: the motions are exact here, so events can be located
// to machine precision and no error accumulates between them.

#include <array>
#include <cmath>
#include <limits>

namespace pb::event_driven {

inline constexpr int kMaxDerivative = 5;
inline constexpr int kMaxModes = 2;

struct Mode {
  double sigma = 0.0;  // decay rate
  double omega = 0.0;  // damped circular frequency
  double a = 0.0;      // coefficient of cos
  double b = 0.0;      // coefficient of sin
  double rr = 0.0, ri = 0.0;  // Re and Im of r, the near-resonant term's coefficient (R_m)
  // Re/Im of (a - i b) (-sigma + i omega)^d, d = 1..kMaxDerivative, and |(a - i b)|,
  // |-sigma + i omega|: derivative coefficients and their bounds.
  std::array<double, kMaxDerivative + 1> re{}, im{};
  std::array<double, kMaxDerivative + 1> envelope{};  // |a - i b| |lambda|^d
};

struct Wave {
  double t0 = 0.0;
  double f0 = 0.0;
  double w = 0.0;  // pulse circular frequency (0: no pulse term)
  double ps = 0.0, pc = 0.0;
  std::array<Mode, kMaxModes> mode{};
  int n_modes = 0;
  // The wave holds up to here (the end of the load it was built for): a near-resonant
  // term grows like t - t0 until then, so its bounds need it.
  double horizon = std::numeric_limits<double>::infinity();
  // Set by prepare(): sin, cos of w t0 and w^d sqrt(ps^2 + pc^2).
  double s0 = 0.0, c0 = 0.0;
  std::array<double, kMaxDerivative + 1> pulse_envelope{};

  // out[d] = f^(d)(t) for d = 0..nd-1 (nd <= kMaxDerivative + 1).
  void eval(double t, double* out, int nd) const;
  double value(double t) const {
    double v;
    eval(t, &v, 1);
    return v;
  }
  // An upper bound of |f^(d)(s)| over all t <= s <= horizon, for 1 <= d <= kMaxDerivative
  // (the damped terms only decay, the pulse term keeps its amplitude, a near-resonant term
  // grows at most like s - t0).
  double bound(double t, int d) const;
  // f(s) = mean() + oscillation with |oscillation| <= swing(t) for t <= s <= horizon: a bound
  // that lets a whole remaining segment be skipped once the motion has decayed.
  double mean() const;
  double swing(double t) const { return bound(t, 0); }
  // Must be called after the coefficients are set and before eval/bound.
  void prepare();
};

// acc += s * x, merging damped terms of identical (sigma, omega). Both waves must share
// t0 and pulse frequency (or have no pulse term). Call prepare() on acc afterwards.
void add_scaled(Wave& acc, const Wave& x, double s);

// The derivative of x as a wave (f0 becomes x'(t0)); prepared.
Wave derivative(const Wave& x);

// Displacement of a damped oscillator  M x'' + C x' + K x = F0 + Fs sin(w t) + Fc cos(w t)
// from x(t0) = x0, x'(t0) = v0 (underdamped: C^2 < 4 K M), valid until the load changes at
// `horizon`. Prepared.
Wave oscillator(double t0, double x0, double v0, double m, double c, double k, double f_const,
                double fs, double fc, double w, double horizon);

// Near resonance, below this |i w - z| / w, the forced response is taken as R_m: there the
// pulse and mode terms would each be over 1 / kNearResonance times the motion they leave,
// which costs the plain form up to ~200 ulps. Set below the damping of every body and
// cluster of the shipped case sets (sigma / w >= 0.0099 at xi = 0.05 and contrasts of
// 1e2), so their results keep the plain form bit for bit.
inline constexpr double kNearResonance = 0.005;

// A quantity that does not move.
Wave constant(double t0, double f0);

}  // namespace pb::event_driven
