#pragma once
// The ground acceleration a_g(t) every solver reads: the one load interface.
//
//   Pulse        what a System holds: the paper's pulses (sine, cosine), the pulse models
//                (makris-a, -b, -c, mp) as sums of at most kMaxSinusoids sinusoids on
//                [0, duration()], and records (samples shared read-only, linear between them).
//                accel, mean and sample are exact; on a record each looks its interval up by
//                a binary search.
//   LoadCursor   the same three for one run, remembering the interval it last looked at: a
//                time-stepper's times march forward, so its lookups cost O(1) amortized
//                (a step back or a jump falls back to the binary search). One per run; it
//                allocates nothing.
//   LoadPiece    what the event-driven reference reads: between two breakpoints the load is a
//                polynomial of degree 1 plus sinusoids in absolute time, so its closed form
//                holds there and each breakpoint is an event (DERIVATION.md §1).
//
// The paper's pulses keep their own formulas everywhere (every stored baseline holds their
// bits); makris-a and makris-b are the same accelerations through the general path, which
// tests compare with them.

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <numbers>

#include "cases/case.hpp"
#include "cases/record.hpp"

namespace pb {

inline constexpr int kMaxSinusoids = 3;

// s sin(w t) + c cos(w t), t absolute.
struct Sinusoid {
  double w = 0.0, s = 0.0, c = 0.0;
  double at(double t) const { return s * std::sin(w * t) + c * std::cos(w * t); }
  // Its integral over [a, b], from half angles: no cancellation for a short interval.
  double integral(double a, double b) const;
};

// a_g on [start, end): value + slope (t - start) + the sinusoids.
struct LoadPiece {
  double start = 0.0;
  double end = std::numeric_limits<double>::infinity();
  double value = 0.0, slope = 0.0;
  std::array<Sinusoid, kMaxSinusoids> waves{};
  int n_waves = 0;

  double accel(double t) const;
};

struct Pulse {
  Pulse() = default;
  // The paper's pulses: Pulse{sine or cosine, s a_p, w_p}.
  Pulse(PulseShape shape_, double amplitude_, double w_) : shape(shape_), amplitude(amplitude_), w(w_) {}

  PulseShape shape = PulseShape::sine;
  double amplitude = 1.0;  // s a_p, signed by the directivity; a record: s alone (its samples are not scaled)
  double w = 1.0;          // w_p
  // The pulse models: a_g = the sum of the waves on [0, length], zero after.
  std::array<Sinusoid, kMaxSinusoids> waves{};
  int n_waves = 0;
  double length = 0.0;
  int cycles = 0;                      // makris-c's n, and mp's gamma and nu (degrees), as the
  double mp_gamma = 0.0, mp_nu = 0.0;  // case gave them: the waves are what solvers read
  // A record: a_g = amplitude times its samples, linear between them.
  std::shared_ptr<const Record> record;

  bool paper() const { return paper_pulse(shape); }
  // Where the load ends: T_p, the model's length, the record's last sample.
  double duration() const {
    if (paper()) return 2.0 * std::numbers::pi / w;
    return record ? record->length() : length;
  }
  // Ground acceleration a_g(t): zero outside [0, duration()] (and before a record's first sample).
  double accel(double t) const {
    if (paper()) {
      if (t < 0.0 || t > duration()) return 0.0;
      return shape == PulseShape::sine ? amplitude * std::sin(w * t) : amplitude * std::cos(w * t);
    }
    return general_accel(t, locate(t));
  }
  // The exact mean of a_g over [t0, t1] (t0 < t1): the ground's impulse per unit mass over
  // a step, divided by the step.
  double mean(double t0, double t1) const;
  // a_g at the step boundary t of a run with step h, for a scheme that samples the load at
  // step ends: a boundary within 1e-9 max(h, T_p) of the load's end counts as the end
  // itself, inside the load (so that T_p = N h ends the pulse on a boundary however N h rounds).
  double sample(double t, double h) const;
  // The piece of the load that holds t (pieces are [start, end)).
  LoadPiece piece(double t) const { return piece_at(t, locate(t)); }
  // The first breakpoint after t (infinity when none is left).
  double next_break(double t) const { return piece(t).end; }

  // A record: the interval i with t_i <= t < t_i+1, clamped to [0, n - 2]; searched from
  // `hint` outwards (a few steps, then by halving). 0 for the other loads.
  std::size_t locate(double t, std::size_t hint = 0) const;
  double general_accel(double t, std::size_t i) const;
  double general_mean(double t0, double t1, std::size_t& i) const;
  LoadPiece piece_at(double t, std::size_t i) const;
};

class LoadCursor {
 public:
  explicit LoadCursor(const Pulse& p) : p_(&p) {}
  double accel(double t) {
    if (p_->paper()) return p_->accel(t);
    i_ = p_->locate(t, i_);
    return p_->general_accel(t, i_);
  }
  double mean(double t0, double t1) { return p_->paper() ? p_->mean(t0, t1) : p_->general_mean(t0, t1, i_); }
  double sample(double t, double h) {
    if (p_->paper()) return p_->sample(t, h);
    const double end = p_->duration();
    return accel(std::abs(t - end) <= 1e-9 * std::max(h, end) ? end : t);
  }
  const Pulse& pulse() const { return *p_; }

 private:
  const Pulse* p_;
  std::size_t i_ = 0;
};

// The phase phi_n of Makris and Chang's type-Cn pulse, a_g = a_p cos(w_p t + phi_n) on
// 0 <= t <= (n + 1/2 - phi_n / pi) T_p: its ground velocity ends at zero by the choice of
// that length, and its displacement ends at zero by phi_n, the root in (0, pi/2) of
// 2 cos(phi) = sin(phi) ((2n + 1) pi - 2 phi).
double makris_phase(int cycles);

// The pulse of a case: the paper's, a pulse model's sinusoids, or a record's samples.
Pulse make_pulse(const Case& c);

}  // namespace pb
