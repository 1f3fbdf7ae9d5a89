#pragma once
// Certified searches on one tracked quantity of a Motion: the first zero crossing and the
// largest |f| (DERIVATION.md §4). The algorithm is the event-driven reference's
// (solvers/event_driven/search.hpp, its DERIVATION.md §2), on a quantity with any number of
// modes: windows bounded by their cubic Hermite interpolant, whose error is at most
// max|f''''| h^4 / 384 (max|f''''| from Motion::bounds), skipped only where that proves
// them free of a crossing (or of a value above the best so far), halved otherwise, down to
// windows of `floor` seconds; roots polished to a sign change of f's rounded values between
// adjacent doubles, maxima at the zero of f' likewise.

#include <vector>

#include "solvers/buildings_reference/motion.hpp"
#include "kit/run_limits.hpp"

namespace pb::buildings {

// Thrown by a search when its Deadline passes, and when a quantity's value or bounds are not
// finite (nothing could be certified).
struct OutOfTime {};
struct NonFinite {};

// Quantity q of a Motion, plus a constant (a neutral contact's noise level).
struct Track {
  Motion* motion = nullptr;
  int q = 0;
  double shift = 0.0;

  void eval(double t, double* out, int nd) const {
    motion->eval(q, t, out, nd);
    out[0] += shift;
  }
  void bounds(double t, double* b) const { motion->bounds(q, t, b); }
  double hermite_error(double t, double h) const { return motion->hermite_error(q, t, h); }
  double mean() const { return motion->mean(q) + shift; }
  double f0() const { return motion->f0(q) + shift; }
  double t0() const { return motion->t0(); }
};

// The first t in (a, b] where f falls to <= 0 after being > 0, to within an ulp; NaN if none.
// If f(a) <= 0 (a contact that has just opened or closed), the search starts where f first
// becomes positive, looking no further than `settle` past a; if it does not by then, f is
// neutral and the event is where it first falls below -noise instead.
double first_root(const Track& f, double a, double b, double floor, double settle, double noise, Deadline& deadline);

struct Peak {
  double value = 0.0;  // largest |f| found
  double t = 0.0;      // where
};

// Raises peak to max |f| on [a, b] if that is larger; interior maxima at the zero of f'.
void max_abs(const Track& f, double a, double b, double floor, Peak& peak, Deadline& deadline);
// Raises up to max f and down to max -f on [a, b] in one search, by max_abs's tests on each
// side: how far a relative displacement goes either way (the free watch of the reference's
// free_motion). Each starts at 0 or above (a motion from rest).
void max_both(const Track& f, double a, double b, double floor, Peak& up, Peak& down, Deadline& deadline);

// max_abs of many quantities of one Motion at once, on one grid: each grid point's window is
// the shortest any quantity still searched asks for, and every quantity is evaluated there from
// one basis (its exponentials and sinusoids: most of an evaluation's cost). A chunk of grid
// points is sampled first, raising each peak to its values, and only then is each window that
// a quantity cannot exclude searched for it alone, as max_abs does: against a peak that is
// already near its final value, most local maxima are excluded without a halving. A quantity
// leaves the grid once its bound over the rest of [a, b] cannot beat its peak. The answers are
// max_abs's (the largest |f| certified to the same tests), found with fewer evaluations.
class PeakSearch {
 public:
  void reserve(int quantities);
  // peaks[i] for quantity qs[i], i < n.
  void run(Motion& m, const int* qs, Peak* peaks, int n, double a, double b, double floor, Deadline& deadline);

 private:
  static constexpr std::size_t kChunk = 64;
  // Presampling (run()): when a quantity's peak is below this fraction of its bound over the
  // segment, at most this many points.
  static constexpr double kPresample = 0.1;
  static constexpr int kMaxPresample = 64;
  std::vector<double> grid_, values_, bounds_, mean_, quiet_;
  std::vector<char> active_;
};

}  // namespace pb::buildings
