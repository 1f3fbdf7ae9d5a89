#pragma once
// Certified searches on one tracked quantity of a Motion: the first zero crossing and the
// largest |f| (DERIVATION.md §4). The algorithm is the event-driven reference's
// (solvers/event_driven/search.hpp, its DERIVATION.md §2), on a quantity with any number of
// modes: windows bounded by their cubic Hermite interpolant, whose error is at most
// max|f''''| h^4 / 384 (max|f''''| from Motion::bounds), skipped only where that proves
// them free of a crossing (or of a value above the best so far), halved otherwise, down to
// windows of `floor` seconds; roots polished to a sign change of f's rounded values between
// adjacent doubles, maxima at the zero of f' likewise.

#include "solvers/buildings_reference/motion.hpp"
#include "solvers/run_limits.hpp"

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

}  // namespace pb::buildings
