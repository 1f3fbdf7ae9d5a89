#pragma once
// Closed-form motion between two events.
//
// Between events every quantity the reference tracks (a body's displacement, a gap, a
// contact force) is a linear combination of a constant, a linear term (a record's load is
// linear between its samples), up to kMaxSines sinusoids at the load's frequencies (the
// paper's pulse has one, a Mavroeidis-Papageorgiou pulse three) and at most two damped
// sinusoids (one per moving cluster of bodies a gap joins):
//
//   f(t) = f0 + lin (t - t0) + sum_j [P_j(t) - P_j(t0)] + sum_m [D_m(t - t0) - D_m(0)]
//   P_j(t)  = ps_j sin(w_j t) + pc_j cos(w_j t)               (absolute time)
//   D_m(s)  = exp(-sigma s) (a cos(omega s) + b sin(omega s))
//   R_mj(s) = Re(r_mj G_mj(s)),  G_mj(s) = (exp(i w_j s) - exp(z s)) / (i w_j - z),  z = -sigma + i omega
//
// R_mj is the forced response from rest of mode m driven near its resonance by sinusoid j
// (|i w_j - z| small against w_j). There P and D_m, each of size 1 / |i w - z|, would cancel to leave a motion
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
inline constexpr int kMaxSines = 3;  // cases/load.hpp's kMaxSinusoids

struct Mode {
  double sigma = 0.0;  // decay rate
  double omega = 0.0;  // damped circular frequency
  double a = 0.0;      // coefficient of cos
  double b = 0.0;      // coefficient of sin
  // |-sigma + i omega| (std::hypot), carried with sigma and omega from the oscillator that
  // made them (add_scaled, derivative): every wave of a frame has its modes, and this hypot
  // per mode per prepare() was a third of a chain's hypot calls. Negative: prepare()
  // computes it. The same function of the same two numbers, so the same value; code that
  // changes sigma or omega of a prepared mode must set it back to -1.
  double rate = -1.0;
  // Re and Im of r_j, the near-resonant term's coefficient with the wave's sinusoid j (R_mj).
  std::array<double, kMaxSines> rr{}, ri{};
  // Re/Im of (a - i b) (-sigma + i omega)^d, d = 1..kMaxDerivative, and |(a - i b)|,
  // |-sigma + i omega|: derivative coefficients and their bounds.
  std::array<double, kMaxDerivative + 1> re{}, im{};
  std::array<double, kMaxDerivative + 1> envelope{};  // |a - i b| |lambda|^d
  // A general mode (DERIVATION.md §10), for a cluster that a yielding body has softened: it
  // may be critically or overdamped, or have no stiffness at all (alpha = 0), where the
  // damped sinusoid above has no frequency. With k_m = K / M and w2 = k_m - sigma^2 of
  // either sign, it is
  //   G(s) = a h0(s) + b h1(s) + c2 h2(s) + c3 h3(s),  h0 = exp(-sigma s) C(s),
  //   h1 = exp(-sigma s) S(s), h2 = integral of h1 from 0, h3 = integral of h2 from 0,
  // C = cos(omega s), S = sin(omega s) / omega for w2 > 0, cosh and sinh / omega for w2 < 0
  // (omega = sqrt|w2|), 1 and s for w2 = 0: the motion from (x0, v0) under the constant and
  // ramp load c2 + c3 s per unit mass is x0 h0 + (v0 + sigma x0) h1 + c2 h2 + c3 h3, with no
  // particular solution F0 / K to cancel. Its derivative is of the same form, (a, b, c2, c3)
  // -> (-sigma a + b, -w2 a - sigma b + c2, c3, 0): re[d], im[d] hold the coefficients of h0
  // and h1 in the d-th derivative. sigma, omega are set as above; rate unused.
  bool general = false;
  double k_m = 0.0, w2 = 0.0;
  double c2 = 0.0, c3 = 0.0;
  // The envelope's decay rate: sigma for w2 >= 0, -lambda_1 = k_m / (sigma + omega) (the
  // slower real root, without cancellation) for w2 < 0; and -lambda_2 = sigma + omega there.
  double slow = 0.0, fast = 0.0;
};

// A sinusoid of the load's: ps sin(w t) + pc cos(w t) in absolute time.
struct Sine {
  double w = 0.0;  // circular frequency
  double ps = 0.0, pc = 0.0;
  double s0 = 0.0, c0 = 1.0;  // set by prepare(): sin, cos of w t0
};

// The transcendental values eval() takes at one t, kept for the other waves evaluated at
// that t. After an event every wave of the frame starts at the event (one t0), so where the
// state is advanced to the next event every body and every gap is evaluated at one tau, on
// a few frequencies and decay rates: at N = 100 that was 500 sin/cos pairs and 300 expm1
// for three distinct pairs and two distinct expm1. Keyed by the argument's bits, so a value
// is libm's for that argument, as eval() without it computes (the results are the same bit
// for bit). Only for a batch of evaluations at one t: a search's points are all distinct,
// where the look-up would be pure cost.
class TrigCache {
 public:
  // sin and cos of x.
  void sin_cos(double x, double& s, double& c);
  double expm1(double x);

 private:
  static constexpr int kSize = 8;  // distinct (sigma, omega) of a chain's clusters, and w
  struct SinCos {
    double x, s, c;
  };
  struct Expm1 {
    double x, e;
  };
  std::array<SinCos, kSize> sc_{};
  std::array<Expm1, kSize> em_{};
  int n_sc_ = 0, n_em_ = 0, next_sc_ = 0, next_em_ = 0;
};

// A wave's value and rate at one t, kept so that any wave that differs from it in f0 alone
// (a cluster's bodies: build_frame gives each the cluster's motion plus its offset,
// Frame::motion) has its value from a few additions instead of an evaluation: eval adds its
// terms to f0 one by one, and value(f0) adds the same terms in the same order, so the bits
// are eval's.
inline constexpr int kMaxTerms = 1 + kMaxSines + kMaxModes * (1 + kMaxSines);
struct WaveAt {
  double rate = 0.0;
  std::array<double, kMaxTerms> term{};
  int n = 0;
  double value(double f0) const;
};

struct Wave {
  double t0 = 0.0;
  double f0 = 0.0;
  double lin = 0.0;  // slope of the linear term lin (t - t0)
  // The load's frequencies, in the order of the load's sinusoids: every wave of a frame has
  // the same list (or none), so a mode's r_j and the sinusoids match by index.
  std::array<Sine, kMaxSines> sine{};
  int n_sines = 0;
  std::array<Mode, kMaxModes> mode{};
  int n_modes = 0;
  // The wave holds up to here (the end of the load it was built for): a near-resonant
  // term grows like t - t0 until then, so its bounds need it.
  double horizon = std::numeric_limits<double>::infinity();
  // Set by prepare(): sum over the sinusoids of w_j^d sqrt(ps_j^2 + pc_j^2).
  std::array<double, kMaxDerivative + 1> pulse_envelope{};
  // Set by prepare(): whether any mode has a near-resonant term (bound() skips their loop).
  bool any_resonant = false;

  // out[d] = f^(d)(t) for d = 0..nd-1 (nd <= kMaxDerivative + 1).
  void eval(double t, double* out, int nd) const;
  // The same values, bit for bit, taking sin, cos and expm1 through `trig` (one t per cache).
  void eval(double t, double* out, int nd, TrigCache& trig) const;
  // eval(t, out, 2, trig) kept as a WaveAt: at.value(f0), at.rate.
  void eval_at(double t, WaveAt& at, TrigCache& trig) const;
  double value(double t) const {
    double v;
    eval(t, &v, 1);
    return v;
  }
  // An upper bound of |f^(d)(s)| over all t <= s <= horizon, for 1 <= d <= kMaxDerivative
  // (the damped terms only decay, the sinusoids keep their amplitudes, a near-resonant term
  // grows at most like s - t0, the linear term has the slope lin and no higher derivative).
  double bound(double t, int d) const;
  // The same bound at t from decay[m] = exp(-sigma_m max(t - t0, 0)) (a general mode's
  // slow rate instead of sigma), which decays(t) writes: a search asks for several d at one
  // t, and the exp per mode per call was a tenth of the reference's time. Bit for bit
  // bound(t, d).
  double bound_at(double t, const double* decay, int d) const;
  void decays(double t, double* decay) const;
  // f(s) = mean() + oscillation with |oscillation| <= swing(t) for t <= s <= horizon: a bound
  // that lets a whole remaining segment be skipped once the motion has decayed. A linear
  // term counts at its value halfway to the horizon, and half its rise in the swing.
  double mean() const;
  double swing(double t) const { return bound(t, 0); }
  // Must be called after the coefficients are set and before eval/bound.
  void prepare();
};

// acc += s * x, merging damped terms of identical (sigma, omega). Both waves must share
// t0 and the load's frequencies (or one have none). Call prepare() on acc afterwards.
void add_scaled(Wave& acc, const Wave& x, double s);

// The derivative of x as a wave (f0 becomes x'(t0)); prepared.
Wave derivative(const Wave& x);

// Displacement of a damped oscillator  M x'' + C x' + K x = F0 + Fs sin(w t) + Fc cos(w t)
// from x(t0) = x0, x'(t0) = v0 (underdamped: C^2 < 4 K M), valid until the load changes at
// `horizon`. Prepared.
Wave oscillator(double t0, double x0, double v0, double m, double c, double k, double f_const,
                double fs, double fc, double w, double horizon);

// The load of a general oscillator: f0 + f1 (t - t0) + sum_j (fs_j sin(w_j t) + fc_j cos(w_j t)).
struct Forcing {
  double f0 = 0.0, f1 = 0.0;
  std::array<double, kMaxSines> w{}, fs{}, fc{};
  int n = 0;
};

// The same oscillator under a load that is a polynomial of degree 1 plus sinusoids (a
// record's segment, a pulse model): the particular solution of the polynomial is one
// (alpha + beta (t - t0), beta = f1 / K, alpha = (f0 - C beta) / K), each sinusoid's is the
// plain one or, near its resonance, R_mj. The paper's pulses keep the function above, whose
// arithmetic the stored baselines hold. Prepared.
Wave oscillator(double t0, double x0, double v0, double m, double c, double k, const Forcing& load, double horizon);

// The oscillator of a cluster that a yielding body has softened (its K from alpha k): any
// damping, K >= 0, as a general mode (Mode::general) under the constant and ramp part of
// the load, each sinusoid with its plain particular solution. Not near a sinusoid's
// resonance (below kNearResonance, use the oscillator above, underdamped there). Prepared.
void general_oscillator_into(Wave& x, double t0, double x0, double v0, double m, double c, double k,
                             const Forcing& load, double horizon);
// Whether general_oscillator_into's cluster is near the resonance of a load's sinusoid.
bool near_resonance(double m, double c, double k, const Forcing& load);

// Both oscillators written into x in place, the same values: a frame rebuilds every free
// body's wave at every event, and a returned Wave (some 650 bytes) was then copied whole.
void oscillator_into(Wave& x, double t0, double x0, double v0, double m, double c, double k, double f_const,
                     double fs, double fc, double w, double horizon);
void oscillator_into(Wave& x, double t0, double x0, double v0, double m, double c, double k, const Forcing& load,
                     double horizon);

// Near resonance, below this |i w - z| / w, the forced response is taken as R_m: there the
// pulse and mode terms would each be over 1 / kNearResonance times the motion they leave,
// which costs the plain form up to ~200 ulps. Set below the damping of every body and
// cluster of the shipped case sets (sigma / w >= 0.0099 at xi = 0.05 and contrasts of
// 1e2), so their results keep the plain form bit for bit.
inline constexpr double kNearResonance = 0.005;

// A quantity that does not move.
Wave constant(double t0, double f0);

// Makes w the constant f0 from t0 in place: the fields past n_sines and n_modes are left as
// they were (nothing reads them; add_scaled clears a sinusoid or mode as it appends one).
// A frame's gaps and forces are rebuilt this way at every event: constant() cleared and
// copied a whole Wave (kMaxModes modes of derivative tables) for each.
void reset(Wave& w, double t0, double f0);

}  // namespace pb::event_driven
