#pragma once
// What the two step loops share, the fixed-size one (stepper.hpp: wall, pair, row3, one
// body alone) and the any-size one (dynamic.hpp: chains and every other row): the step mean
// of the ground load, the number of steps of a run, and the tally a Result is made from.

#include <algorithm>
#include <cmath>

#include "cases/system.hpp"
#include "kit/fixed_step.hpp"

namespace pb::moreau_jean {

// cos/sin(w_p t_k) are recomputed exactly every kResync steps; in between they come from
// a rotation by w_p h. The drift of a rotation is at most ~3 ulp per step, so the load is
// within kResync * 3 * 2^-53 ~ 2e-14 of a_p (measured 4e-15: test PulseMeanRecurrence*).
inline constexpr long kResync = 64;

// How a step's ground load abar_k is formed (Settings::variant of moreau-jean):
//   step_mean    the exact mean of a_g over [t_k, t_k+1] (the default, see README)
//   end_samples  (1 - theta) a_g(t_k) + theta a_g(t_k+1), the theta-weighted end samples of
//                Siconos' MoreauJeanOSI (variant end-samples): for comparing with it
enum class LoadRule { step_mean, end_samples };

// The step mean of the ground acceleration, abar_k = (1/h) integral over [t_k, t_k+1] of a_g.
// A step inside the pulse: abar = p cos(w t_k) + r sin(w t_k). The step that contains
// T_p integrates only up to T_p, where cos = 1 and sin = 0 exactly.
// With LoadRule::end_samples the loaded steps are k = 0 .. full_steps and end_mean(k) gives
// their load (std::sin/cos at every sample: this rule is for comparisons, not for speed).
// Any other load (a record, a pulse model: `general`) is read through a LoadCursor over the
// full_steps steps that reach its end: the exact step mean (a record's trapezoids), or the
// end samples, at O(1) a step.
struct PulseLoad {
  double wh = 0.0;                                  // w_p h
  double cos_wh = 1.0, sin_wh = 0.0;                // the rotation of one step
  double p = 0.0, r = 0.0;                          // full step
  double tail_c = 0.0, tail_s = 0.0, tail_1 = 0.0;  // step that contains T_p: tail_c cos + tail_s sin + tail_1
  long full_steps = 0;                              // steps 0 .. full_steps-1 lie inside [0, T_p]
  bool straddle = false;                            // step full_steps contains T_p inside it
  LoadRule rule = LoadRule::step_mean;
  bool general = false;                             // not the paper's pulse
  double theta = 0.5, h = 0.0;  // end_samples: the weight of the end sample, the step
  Pulse pulse;

  double tail(long k) const {
    const double phase = static_cast<double>(k) * wh;
    return tail_c * std::cos(phase) + tail_s * std::sin(phase) + tail_1;
  }
  // end_samples: the load of step k, from a_g at t_k = k h and t_k+1 (Pulse::sample).
  double end_mean(long k) const {
    const double t0 = static_cast<double>(k) * h, t1 = static_cast<double>(k + 1) * h;
    return (1.0 - theta) * pulse.sample(t0, h) + theta * pulse.sample(t1, h);
  }
  // The exact step mean of step k, what StepMonitor counts as the ground's work.
  double exact_mean(long k) const { return pulse.mean(static_cast<double>(k) * h, static_cast<double>(k + 1) * h); }
};

inline PulseLoad make_pulse_load(const Pulse& pulse, double h, LoadRule rule = LoadRule::step_mean,
                                 double theta = 0.5) {
  PulseLoad l;
  l.rule = rule;
  l.theta = theta;
  l.h = h;
  l.pulse = pulse;
  if (!pulse.paper()) {
    l.general = true;
    l.full_steps = static_cast<long>(std::ceil(pulse.duration() / h));
    return l;
  }
  l.wh = pulse.w * h;
  l.cos_wh = std::cos(l.wh);
  l.sin_wh = std::sin(l.wh);
  // (1 - cos x) / x and sin x / x, without the cancellation of 1 - cos x.
  const double half = std::sin(0.5 * l.wh);
  const double alpha = 2.0 * half * half / l.wh, beta = l.sin_wh / l.wh;
  const double a = pulse.amplitude, a_wh = a / l.wh;
  if (pulse.shape == PulseShape::sine) {  // mean of sin = (cos(w t_k) - cos(w t_k+1)) / (w h)
    l.p = a * alpha;
    l.r = a * beta;
    l.tail_c = a_wh;
    l.tail_1 = -a_wh;
  } else {  // mean of cos = (sin(w t_k+1) - sin(w t_k)) / (w h)
    l.p = a * beta;
    l.r = -a * alpha;
    l.tail_s = -a_wh;
  }
  // A pulse that ends within 1e-9 steps of a step boundary ends on it: the dropped sliver
  // changes the impulse by < 1e-9 h a_p, and T_p = N h (t_min = T_p) lands there exactly.
  const double ratio = pulse.duration() / h;
  const double nearest = std::round(ratio);
  if (std::abs(ratio - nearest) <= 1e-9 * std::max(1.0, ratio)) {
    l.full_steps = static_cast<long>(nearest);
    l.straddle = false;
  } else {
    l.full_steps = static_cast<long>(std::floor(ratio));
    l.straddle = true;
  }
  return l;
}

// The step means of the full pulse steps, in order from step k: cos/sin(w_p t_k) come from
// the rotation, and are recomputed exactly at k and at every multiple of kResync.
struct PulseMeans {
  const PulseLoad& l;
  long k;
  double c = 1.0, s = 0.0;

  PulseMeans(const PulseLoad& load, long first) : l(load), k(first) { resync(); }
  void resync() {
    const double phase = static_cast<double>(k) * l.wh;
    c = std::cos(phase);
    s = std::sin(phase);
  }
  // Forced inline: in the fixed-size loop a call costs as much as the step.
  [[gnu::always_inline]] inline double next() {
    if (k % kResync == 0) resync();
    const double abar = l.p * c + l.r * s;
    const double c_next = c * l.cos_wh - s * l.sin_wh;
    s = s * l.cos_wh + c * l.sin_wh;
    c = c_next;
    ++k;
    return abar;
  }
};

// The counts a Result is made from: the shell's (kit/fixed_step.hpp), filled here by the
// scheme's own inner loops.
using Tally = StepTally;

// Runs the steps from k (the state's step, which `step` advances) to k_end, giving each the
// ground load its rule makes: step(applied, exact) -> bool, with `applied` the load the
// scheme uses and `exact` the step mean that the energy monitor counts (the same value
// under LoadRule::step_mean). Stops at the first step that returns false. Both step loops
// (stepper.hpp, dynamic.cpp) run through this; forced inline, so that the loop and the
// step are one function.
template <typename Step>
[[gnu::always_inline]] inline bool drive(const PulseLoad& l, const long& k, long k_end, Step&& step) {
  bool ok = true;
  if (l.general) {
    LoadCursor load(l.pulse);
    const long loaded_end = std::min(k_end, l.full_steps + 1);  // + 1: an end sample at the load's end
    while (ok && k < loaded_end) {
      const double t0 = static_cast<double>(k) * l.h, t1 = static_cast<double>(k + 1) * l.h;
      const double exact = load.mean(t0, t1);
      ok = l.rule == LoadRule::end_samples
               ? step((1.0 - l.theta) * load.sample(t0, l.h) + l.theta * load.sample(t1, l.h), exact)
               : step(exact, exact);
    }
  } else if (l.rule == LoadRule::end_samples) {
    const long loaded_end = std::min(k_end, l.full_steps + 1);
    while (ok && k < loaded_end) ok = step(l.end_mean(k), l.exact_mean(k));
  } else {
    if (k < l.full_steps) {
      PulseMeans means(l, k);
      const long pulse_end = std::min(k_end, l.full_steps);
      while (ok && k < pulse_end) {
        const double abar = means.next();
        ok = step(abar, abar);
      }
    }
    if (ok && l.straddle && k == l.full_steps && k < k_end) {
      const double abar = l.tail(k);
      ok = step(abar, abar);
    }
  }
  while (ok && k < k_end) ok = step(0.0, 0.0);
  return ok;
}

}  // namespace pb::moreau_jean
