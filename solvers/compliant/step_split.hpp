#pragma once
// Where the compliant solver's Newmark integrator splits a step, shared by its single
// oscillators' engine (newmark.cpp) and its buildings' (buildings_newmark.cpp): the load's
// jumps, and the first time a contact element's state stops matching its motion within a
// solved (sub-)step.

#include <algorithm>
#include <vector>

#include "cases/load.hpp"

namespace pb::compliant {

// Newton's iteration, the same in both engines: iterations before a step is given up, and the
// correction (over a_p / w_p^2 plus the largest |u|) below which an iterate counts as converged.
inline constexpr int kNewtonIterations = 50;
inline constexpr double kNewtonTolerance = 1e-13;

// Contact changes one step may hold before the run is given up: each is a sub-step, and a
// step that resolves nothing of the contact could otherwise split without end.
inline constexpr int kMaxEventsPerStep = 64;
// An event this close to a (sub-)step's start (a fraction of the whole step) switches the
// element there without a sub-step: a step of that length would only add round-off.
inline constexpr double kTinyFraction = 1e-9;

// Where the load jumps, and its values just before and after: the end of every load (the
// paper's cosine pulse ends at s a_p, a record at its last sample), and a record's first
// sample when it comes after t = 0 (at t = 0 the start's acceleration is the load's there
// already). The trapezoidal rule is second order for a smooth load and across a kink (a
// record's samples: one kink per sample whatever the step, each an O(h^3) error), but a
// jump it integrates to O(h), and an acceleration carried across it from the load before
// was an O(h) error in every later velocity: the cosine pulse's Pi1 erred 6.6e-4, 1.6e-4,
// 4.1e-5 at N = 1024, 4096, 16384 (the sine's, continuous, 4.6e-6, 2.7e-7, 1.7e-8).
struct LoadJump {
  double t, before, after;
};

inline std::vector<LoadJump> load_jumps(const Pulse& p) {
  std::vector<LoadJump> jumps;
  if (p.record && p.record->t.front() > 0.0)
    jumps.push_back({p.record->t.front(), 0.0, p.accel(p.record->t.front())});
  const double end = p.duration();
  jumps.push_back({end, p.accel(end), 0.0});
  std::erase_if(jumps, [](const LoadJump& j) { return j.before == j.after; });
  return jumps;
}

// Samples of each penetration's interpolant per (sub-)step, the bracket a contact change is
// bisected in: a contact shorter than 1/8 of a step can be missed, as at the steps' ends.
inline constexpr int kEventSamples = 8;

// A penetration's cubic Hermite interpolant over a (sub-)step of length h, from p0, q0 to
// p1, q1; side +1 for an open element (its state stops matching once it overlaps while
// approaching), -1 for a closed one (once apart while parting).
struct PenetrationCubic {
  double p0, q0, p1, q1, h, side;
  bool mismatch(double s) const {
    const double s2 = s * s, s3 = s2 * s;
    const double p = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * h * q0 + (-2 * s3 + 3 * s2) * p1 +
                     (s3 - s2) * h * q1;
    const double dp = ((6 * s2 - 6 * s) * p0 + (-6 * s2 + 6 * s) * p1) / h + (3 * s2 - 4 * s + 1) * q0 +
                      (3 * s2 - 2 * s) * q1;
    return side * p > 0.0 && side * dp > 0.0;
  }
  // The first mismatch before `before` (bisected between samples to round-off), or 2.
  double first_mismatch(double before) const {
    double lo = 0.0;
    for (int k = 1; k <= kEventSamples; ++k) {
      const double hi = static_cast<double>(k) / kEventSamples;
      if (lo >= before) return 2.0;
      if (!mismatch(hi)) {
        lo = hi;
        continue;
      }
      if (mismatch(0.0)) return 0.0;  // at the start already (round-off there): switch now
      double a = lo, b = hi;
      for (int it = 0; it < 60 && b - a > 1e-15; ++it) {
        const double mid = 0.5 * (a + b);
        (mismatch(mid) ? b : a) = mid;
      }
      return b;
    }
    return 2.0;
  }
};

}  // namespace pb::compliant
