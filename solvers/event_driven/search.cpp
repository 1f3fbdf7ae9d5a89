#include "solvers/event_driven/search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pb::event_driven {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Point {
  double t, f, df;
};

Point at(const Wave& w, double t) {
  double v[2];
  w.eval(t, v, 2);
  return {t, v[0], v[1]};
}

// Coefficients of the cubic Hermite interpolant on s in [0, 1].
struct Cubic {
  double c0, c1, c2, c3;
  Cubic(const Point& a, const Point& b) {
    const double h = b.t - a.t;
    c0 = a.f;
    c1 = h * a.df;
    c2 = 3.0 * (b.f - a.f) - h * (2.0 * a.df + b.df);
    c3 = 2.0 * (a.f - b.f) + h * (a.df + b.df);
  }
  double operator()(double s) const { return c0 + s * (c1 + s * (c2 + s * c3)); }
  // Min and max over [0, 1]: the ends and the stationary points inside.
  void range(double& lo, double& hi) const {
    lo = std::min(c0, (*this)(1.0));
    hi = std::max(c0, (*this)(1.0));
    auto visit = [&](double s) {
      if (s > 0.0 && s < 1.0) {
        const double v = (*this)(s);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    };
    // c1 + 2 c2 s + 3 c3 s^2 = 0
    const double qa = 3.0 * c3, qb = 2.0 * c2, qc = c1;
    if (std::abs(qa) < 1e-300) {
      if (qb != 0.0) visit(-qc / qb);
      return;
    }
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc < 0.0) return;
    const double r = std::sqrt(disc);
    const double q = -0.5 * (qb + std::copysign(r, qb));
    if (q != 0.0) {
      visit(q / qa);
      visit(qc / q);
    } else {
      visit(0.0);
    }
  }
};

double hermite_error(const Wave& w, double a, double h) {
  const double h2 = h * h;
  return w.bound(a, 4) * h2 * h2 / 384.0;
}

// Root of g on [lo, hi] with g(lo) > 0 >= g(hi), g monotone there: safeguarded Newton.
// Returns the smallest representable t found with g(t) <= 0.
double refine_root(const Wave& g, Point lo, Point hi) {
  double t = hi.t;
  for (int it = 0; it < 100 && hi.t - lo.t > 2.0 * std::numeric_limits<double>::epsilon() * std::abs(hi.t); ++it) {
    // Newton from the end with the larger slope information, clamped to the bracket.
    const Point& p = std::abs(lo.f) < std::abs(hi.f) ? lo : hi;
    double next = p.df != 0.0 ? p.t - p.f / p.df : 0.5 * (lo.t + hi.t);
    if (!(next > lo.t && next < hi.t)) next = 0.5 * (lo.t + hi.t);
    const Point q = at(g, next);
    if (q.f > 0.0)
      lo = q;
    else
      hi = q;
    t = hi.t;
    if (q.f == 0.0) break;
  }
  return t;
}

// One unit of search work: ends the search once the deadline has passed.
void tick(Deadline& deadline) {
  if (deadline.tick()) throw OutOfTime{};
}

// Depth-first search of [a, b] for the first crossing, left half first.
double search(const Wave& g, const Point& a, const Point& b, double floor, Deadline& dl) {
  tick(dl);
  const double h = b.t - a.t;
  if (b.f <= 0.0) {
    // A crossing is bracketed; it is the first one if g is monotone on the window.
    if (std::abs(a.df) > g.bound(a.t, 2) * h || h <= floor) return refine_root(g, a, b);
  } else {
    double lo, hi;
    Cubic(a, b).range(lo, hi);
    if (lo - hermite_error(g, a.t, h) > 0.0) return kNaN;
    if (h <= floor) return kNaN;  // a touch within round-off, not a contact
  }
  const Point m = at(g, 0.5 * (a.t + b.t));
  if (m.f <= 0.0) {
    const double r = search(g, a, m, floor, dl);
    return std::isnan(r) ? refine_root(g, a, m) : r;
  }
  const double r = search(g, a, m, floor, dl);
  return std::isnan(r) ? search(g, m, b, floor, dl) : r;
}

// Window length for which the Hermite error is a fraction of the current value.
double window(const Wave& g, double t, double f, double rest) {
  const double b4 = g.bound(t, 4);
  if (b4 <= 0.0) return rest;
  return std::min(rest, std::sqrt(std::sqrt(96.0 * std::abs(f) / b4)));
}

// A wave whose value or bounds are not finite certifies nothing (and would make every
// exclusion test false, halving windows down to the floor everywhere).
void check_finite(const Wave& f, const Point& p) {
  if (!std::isfinite(p.f) || !std::isfinite(p.df) || !std::isfinite(f.bound(p.t, 4))) throw NonFinite{};
}

double crossing(const Wave& f, Point p, double b, double floor, Deadline& dl);
double first_crossing(const Wave& f, const Point& p, double b, double floor, Deadline& dl);

}  // namespace

double first_root(const Wave& f, double a, double b, double floor, double settle, double noise, Deadline& dl) {
  Point p = at(f, a);
  check_finite(f, p);
  if (p.f > 0.0) return first_crossing(f, p, b, floor, dl);
  if (p.f < -noise) return a;
  for (double step = floor;; step *= 2.0) {
    const double t = std::min(a + step, b);
    p = at(f, t);
    if (p.f > 0.0) return first_crossing(f, p, b, floor, dl);
    if (step > settle || t == b) break;
  }
  // Neutral: the event is where f first falls below -noise. Shifted once: if that leaves
  // f(a) at or below zero (f(a) is -noise already, or noise is below f's round-off), the
  // event is now.
  Wave shifted = f;
  shifted.f0 += noise;
  shifted.prepare();
  p = at(shifted, a);
  if (!(p.f > 0.0)) return a;
  return first_crossing(shifted, p, b, floor, dl);
}

namespace {

double first_crossing(const Wave& f, const Point& p, double b, double floor, Deadline& dl) {
  // Far from a root the whole search is skipped: f >= f(a) + f'(a) s - max|f''| s^2 / 2,
  // and when that stays clear of f's rounding (relative to its terms) up to b, no
  // evaluation on (a, b] can come out <= 0. Every contact is searched at every event, and
  // most are far from closing or detaching.
  const double h = b - p.t;
  const double low = p.f + std::min(0.0, p.df * h) - 0.5 * f.bound(p.t, 2) * h * h;
  if (low > 1e-10 * (std::abs(f.f0) + 2.0 * f.bound(f.t0, 0))) return kNaN;
  return crossing(f, p, b, floor, dl);
}

// The first crossing after p, where f(p) > 0.
double crossing(const Wave& f, Point p, double b, double floor, Deadline& dl) {
  const double mean = f.mean();
  while (p.t < b) {
    tick(dl);
    if (mean - f.swing(p.t) > 0.0) return kNaN;
    const double h = std::max(window(f, p.t, p.f, b - p.t), std::min(floor, b - p.t));
    const double tb = h >= b - p.t ? b : p.t + h;
    const Point q = at(f, tb);
    const double r = search(f, p, q, floor, dl);
    if (!std::isnan(r)) return r;
    p = q;
  }
  return kNaN;
}

}  // namespace

namespace {

void consider(const Point& p, Peak& peak) {
  if (std::abs(p.f) > peak.value) {
    peak.value = std::abs(p.f);
    peak.t = p.t;
  }
}

// Zero of f' between a and b where f' changes sign (f'' of one sign): Newton-bisection.
Point stationary(const Wave& f, Point a, Point b) {
  for (int it = 0; it < 100 && b.t - a.t > 2.0 * std::numeric_limits<double>::epsilon() * std::abs(b.t); ++it) {
    double v[3];
    const double mid = 0.5 * (a.t + b.t);
    f.eval(mid, v, 3);
    double next = v[2] != 0.0 ? mid - v[1] / v[2] : mid;
    if (!(next > a.t && next < b.t)) next = mid;
    const Point q = at(f, next);
    if ((q.df > 0.0) == (a.df > 0.0))
      a = q;
    else
      b = q;
    if (q.df == 0.0) return q;
  }
  return std::abs(a.df) < std::abs(b.df) ? a : b;
}

void peak_search(const Wave& f, const Point& a, const Point& b, double floor, Peak& peak, Deadline& dl) {
  tick(dl);
  const double h = b.t - a.t;
  double lo, hi;
  Cubic(a, b).range(lo, hi);
  if (std::max(-lo, hi) + hermite_error(f, a.t, h) <= peak.value) return;
  if (h <= floor) return;
  // f monotone: the ends, already considered, hold the max.
  if (std::abs(a.df) > f.bound(a.t, 2) * h) return;
  if ((a.df > 0.0) != (b.df > 0.0)) {
    double v[3];
    f.eval(a.t, v, 3);
    // f'' of one sign on the window: exactly one stationary point inside.
    if (std::abs(v[2]) > f.bound(a.t, 3) * h) {
      consider(stationary(f, a, b), peak);
      return;
    }
  }
  const Point m = at(f, 0.5 * (a.t + b.t));
  consider(m, peak);
  peak_search(f, a, m, floor, peak, dl);
  peak_search(f, m, b, floor, peak, dl);
}

}  // namespace

void max_abs(const Wave& f, double a, double b, double floor, Peak& peak, Deadline& dl) {
  Point p = at(f, a);
  check_finite(f, p);
  consider(p, peak);
  const double mean = std::abs(f.mean());
  while (p.t < b) {
    tick(dl);
    if (mean + f.swing(p.t) <= peak.value) return;
    const double ref = std::max(peak.value, std::abs(p.f));
    const double h = std::max(window(f, p.t, ref, b - p.t), std::min(floor, b - p.t));
    const Point q = at(f, h >= b - p.t ? b : p.t + h);
    consider(q, peak);
    peak_search(f, p, q, floor, peak, dl);
    p = q;
  }
}

}  // namespace pb::event_driven
