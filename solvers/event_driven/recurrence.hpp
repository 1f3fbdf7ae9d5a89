#pragma once
// The exact update of a damped oscillator over an interval whose load is linear, as a
// recurrence (Nigam and Jennings 1969): what the reference's closed form gives at the
// interval's end, written as a 2x2 state-transition matrix plus the load's two terms,
// precomputed per oscillator and interval length. A recorded ground motion is linear
// between its samples, and a sample interval in which no event can happen is taken this
// way: a few products per body instead of a frame rebuilt and searched (DERIVATION.md §11).
//
// With it, a bound of the acceleration over the interval from the state at its start (the
// acceleration of a linear oscillator under a linear load is itself a free damped
// oscillation, whose energy only decays): what lets the reference prove that no event lies
// inside, or run its full searches where it cannot.

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace pb::event_driven {

// Over [0, h], per unit mass: x'' + 2 sigma x' + w2 x = q0 + q1 s. The increments
// dx = d[0][0] x0 + d[0][1] v0 + d[0][2] q0 + d[0][3] q1 and dv likewise from d[1].
struct Transition {
  double h = std::numeric_limits<double>::quiet_NaN();
  double d[2][4] = {};
};

// The transition over h of x'' + two_sigma x' + w2 x = q0 + q1 s, computed in long double
// from the exponential of the augmented (balanced) 4x4 system, its Taylor series scaled and
// squared on exp(A) - I: every entry to a relative accuracy near double's, where the closed
// form would cancel (the ramp's term is h^3 / 6 out of terms of size h). For tests too.
Transition transition(double two_sigma, double w2, double h);

// The distinct interval lengths a run meets, numbered as they first appear: a record's
// sample times t_i = i DT, rounded to doubles, have some 15 distinct differences over 40 s.
// An open-addressed table on the bits of h: one look-up per interval serves every body.
class Lengths {
 public:
  static constexpr int kMax = 64;  // beyond, slot() says no: an unevenly sampled record
  Lengths() { clear(); }
  // h's number, from 0; -1 when kMax lengths are already numbered.
  int slot(double h) {
    std::uint64_t bits;
    std::memcpy(&bits, &h, sizeof bits);
    std::size_t at = static_cast<std::size_t>((bits * 0x9E3779B97F4A7C15ull) >> 57);  // 0..127
    for (;; at = (at + 1) & (kTable - 1)) {
      if (id_[at] < 0) break;
      if (key_[at] == bits) return id_[at];
    }
    if (n_ == kMax) return -1;
    key_[at] = bits;
    id_[at] = n_;
    return n_++;
  }
  void clear() {
    id_.fill(-1);
    n_ = 0;
  }

 private:
  static constexpr std::size_t kTable = 128;  // twice kMax: probes stay short
  std::array<std::uint64_t, kTable> key_{};
  std::array<int, kTable> id_{};
  int n_ = 0;
};

// One oscillator (m, c, k: the recurrence holds for any c >= 0, k > 0) and its transitions
// per interval length (numbered by Lengths).
class Recurrence {
 public:
  Recurrence(double m, double c, double k);
  // Whether it applies: k > 0 and every coefficient finite.
  bool valid() const { return valid_; }
  double two_sigma() const { return two_sigma_; }  // c / m
  double w2() const { return w2_; }                // k / m
  double w() const { return w_; }                  // sqrt(w2)

  // The transition over h, numbered `slot`, computed on first use and kept.
  const Transition& over(int slot, double h) {
    const auto k = static_cast<std::size_t>(slot);
    if (k < by_slot_.size() && by_slot_[k].h == h) return by_slot_[k];
    if (k >= by_slot_.size()) by_slot_.resize(k + 1);
    by_slot_[k] = transition(two_sigma_, w2_, h);
    return by_slot_[k];
  }

  struct Step {
    double dx, dv;  // the increments of x and v over the interval
    double acc;     // an upper bound of |x''| over the interval
  };
  // From x0, v0 under q0 + q1 s over the transition's h.
  Step step(const Transition& t, double x0, double v0, double q0, double q1) const {
    Step out;
    out.dx = t.d[0][0] * x0 + t.d[0][1] * v0 + t.d[0][2] * q0 + t.d[0][3] * q1;
    out.dv = t.d[1][0] * x0 + t.d[1][1] * v0 + t.d[1][2] * q0 + t.d[1][3] * q1;
    out.acc = acceleration_bound(x0, v0, q0, q1);
    return out;
  }

  // An upper bound W of |x''(s)| for s >= 0 while the load stays q0 + q1 s: y = x'' obeys
  // y'' + 2 sigma y' + w2 y = q'' = 0, whose energy (y'^2 + w2 y^2) / 2 does not grow, so
  // |y(s)| <= sqrt(y(0)^2 + y'(0)^2 / w2) = W, and the jerk |y'(s)| <= w() W. Widened by a
  // relative 1e-9 and an absolute 1e-14 of its terms' sizes for its own round-off (a few
  // ulps of those terms, whatever their sum cancels).
  double acceleration_bound(double x0, double v0, double q0, double q1) const {
    const double y0 = q0 - two_sigma_ * v0 - w2_ * x0;
    const double y1 = q1 - two_sigma_ * y0 - w2_ * v0;
    const double size0 = std::abs(q0) + std::abs(two_sigma_ * v0) + std::abs(w2_ * x0);
    const double size1 = std::abs(q1) + two_sigma_ * size0 + std::abs(w2_ * v0);
    return (1.0 + 1e-9) * std::sqrt(y0 * y0 + y1 * y1 * inv_w2_) + 1e-14 * (size0 + size1 * inv_w_);
  }

 private:
  double two_sigma_ = 0.0, w2_ = 0.0, w_ = 0.0, inv_w2_ = 0.0, inv_w_ = 0.0;
  bool valid_ = false;
  std::vector<Transition> by_slot_;
};

}  // namespace pb::event_driven
