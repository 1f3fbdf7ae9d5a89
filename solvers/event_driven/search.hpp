#pragma once
// Certified searches on a closed-form Wave: the first zero crossing and the largest |f|.
//
// Both cut the interval into windows and bound f on each window by its cubic Hermite
// interpolant through (f, f') at the window's ends, whose error is at most
// max|f''''| w^4 / 384 at the middle and vanishes at the ends (max|f''''| is bounded from
// the wave's amplitudes, bound()).
// A window is skipped only when that bound proves it holds no crossing (or no value
// above the best so far); otherwise it is halved. Sampling alone could step over a
// grazing approach; this cannot, down to windows of `floor` seconds, where a touch is
// within round-off of the gap.

#include "solvers/event_driven/wave.hpp"
#include "kit/run_limits.hpp"

namespace pb::event_driven {

// Thrown by a search when its Deadline passes (Settings::time_limit, Settings::stop): a
// search of a grazing approach may halve its windows down to the floor, and the run must
// still end when it is told to.
struct OutOfTime {};
// Thrown when a wave's value or bounds are not finite: no search could certify anything.
struct NonFinite {};

// The first t in (a, b] where f falls to <= 0 after being > 0, to within an ulp of the
// root; NaN if there is none. If f(a) <= 0 (a contact that has just opened or closed, up
// to round-off), the search starts where f first becomes positive, looking no further
// than `settle` past a. If it does not become positive by then, f is taken as neutral
// (a resting contact with zero force, a gap that stays closed) and the event is where it
// first falls below -noise instead.
double first_root(const Wave& f, double a, double b, double floor, double settle, double noise, Deadline& deadline);

struct Peak {
  double value = 0.0;  // largest |f| found
  double t = 0.0;      // where
};

// Raises peak to max |f| on [a, b] if that is larger; interior maxima are located at the
// zero of f' to within an ulp.
void max_abs(const Wave& f, double a, double b, double floor, Peak& peak, Deadline& deadline);
// Raises up to max f and down to max -f on [a, b], in one search: how far a relative
// displacement goes either way. Each value starts at 0 or above (a motion from rest).
void max_both(const Wave& f, double a, double b, double floor, Peak& up, Peak& down, Deadline& deadline);

namespace detail {
// The searches' last stages, for tests: the root of f on lo < hi with f(lo) > 0 >= f(hi)
// and f monotone there (first_root's), and the stationary point of f on a < b with f' of
// opposite signs at the ends and f'' of one sign (max_abs's: {|f|, t} where it stops).
double polish_root(const Wave& f, double lo, double hi);
Peak polish_stationary(const Wave& f, double a, double b);
}  // namespace detail

}  // namespace pb::event_driven
