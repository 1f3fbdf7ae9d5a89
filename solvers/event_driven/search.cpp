#include "solvers/event_driven/search.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "kit/hermite_search.hpp"

namespace pb::event_driven {

namespace {

using hermite::Bracket;
using hermite::Cubic;
using hermite::edge_range;
using hermite::next_down;
using hermite::next_up;
using hermite::polish;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Point {
  double t, f, df;
  double ddf = std::numeric_limits<double>::quiet_NaN();  // f'', where the caller needs it
};

Point at(const Wave& w, double t) {
  double v[2];
  w.eval(t, v, 2);
  return {t, v[0], v[1]};
}

// With f'' too: the peak search needs it wherever f' changes sign, and it costs a few
// products more than f and f' (their values are the same as at()'s).
Point at3(const Wave& w, double t) {
  double v[3];
  w.eval(t, v, 3);
  return {t, v[0], v[1], v[2]};
}

// A wave's bounds kept for the last t asked: the searches ask for several derivatives at
// one window's start (its Hermite error, its monotonicity, the next window's length), some
// twice, and each bound(t, d) took an exp per mode. Bit for bit bound().
class Bounds {
 public:
  explicit Bounds(const Wave& w) : w_(w) {}
  double operator()(double t, int d) {
    if (!(t == t_)) {
      w_.decays(t, decay_);
      t_ = t;
      known_ = 0;
    }
    if (!(known_ & (1u << d))) {
      value_[d] = w_.bound_at(t_, decay_, d);
      known_ |= 1u << d;
    }
    return value_[d];
  }

 private:
  const Wave& w_;
  double t_ = std::numeric_limits<double>::quiet_NaN();
  double decay_[kMaxModes] = {};
  double value_[kMaxDerivative + 1] = {};
  unsigned known_ = 0;  // bit d: value_[d] is bound_at(t_, decay_, d)
};

// Coefficients of the cubic Hermite interpolant on s in [0, 1].
double hermite_error(Bounds& bound, double a, double h) {
  const double h2 = h * h;
  return bound(a, 4) * h2 * h2 / 384.0;
}

double refine_root(const Wave& g, const Point& lo, const Point& hi) {
  return polish([&](double t) { return at(g, t); }, lo, hi).hi.t;
}

// Whether y (f' or f'') keeps one sign on a window of length h, given y at its ends and a
// bound d on |y'| there: y >= y(a) - d (t - a) and y >= y(b) - d (b - t), whose larger is
// at least (y(a) + y(b) - d h) / 2 (for y > 0 at both ends; alike below zero). The end a
// alone, |y(a)| > d h, was the old test; both ends pass windows up to twice as long, each
// one a halving and an evaluation saved.
bool one_sign(double ya, double yb, double d, double h) {
  if (std::abs(ya) > d * h) return true;
  return ya != 0.0 && (ya > 0.0) == (yb > 0.0) && std::abs(ya) + std::abs(yb) > d * h;
}

// One unit of search work: ends the search once the deadline has passed.
void tick(Deadline& deadline) {
  if (deadline.tick()) throw OutOfTime{};
}

// Depth-first search of [a, b] for the first crossing, left half first.
double search(const Wave& g, Bounds& bound, const Point& a, const Point& b, double floor, Deadline& dl) {
  tick(dl);
  const double h = b.t - a.t;
  if (b.f <= 0.0) {
    // A crossing is bracketed; it is the first one if g is monotone on the window.
    if (one_sign(a.df, b.df, bound(a.t, 2), h) || h <= floor) return refine_root(g, a, b);
  } else {
    const Cubic cubic(a, b);
    double lo, hi;
    cubic.range(lo, hi);
    const double err = hermite_error(bound, a.t, h);
    if (lo - err > 0.0) return kNaN;
    if (h <= floor) return kNaN;  // a touch within round-off, not a contact
    edge_range(cubic, err, lo, hi);
    if (lo > 0.0) return kNaN;
  }
  const Point m = at(g, 0.5 * (a.t + b.t));
  if (m.f <= 0.0) {
    const double r = search(g, bound, a, m, floor, dl);
    return std::isnan(r) ? refine_root(g, a, m) : r;
  }
  const double r = search(g, bound, a, m, floor, dl);
  return std::isnan(r) ? search(g, bound, m, b, floor, dl) : r;
}

// Window length for which the Hermite error is a fraction of the current value.
double window(Bounds& bound, double t, double f, double rest) {
  const double b4 = bound(t, 4);
  if (b4 <= 0.0) return rest;
  return std::min(rest, std::sqrt(std::sqrt(96.0 * std::abs(f) / b4)));
}

// A wave whose value or bounds are not finite certifies nothing (and would make every
// exclusion test false, halving windows down to the floor everywhere).
void check_finite(Bounds& bound, const Point& p) {
  if (!std::isfinite(p.f) || !std::isfinite(p.df) || !std::isfinite(bound(p.t, 4))) throw NonFinite{};
}

double crossing(const Wave& f, Bounds& bound, Point p, double b, double floor, Deadline& dl);
double first_crossing(const Wave& f, Bounds& bound, const Point& p, double b, double floor, Deadline& dl);

}  // namespace

double first_root(const Wave& f, double a, double b, double floor, double settle, double noise, Deadline& dl) {
  Point p = at(f, a);
  Bounds bound(f);
  check_finite(bound, p);
  if (p.f > 0.0) return first_crossing(f, bound, p, b, floor, dl);
  if (p.f < -noise) return a;
  for (double step = floor;; step *= 2.0) {
    const double t = std::min(a + step, b);
    p = at(f, t);
    if (p.f > 0.0) return first_crossing(f, bound, p, b, floor, dl);
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
  Bounds shifted_bound(shifted);
  return first_crossing(shifted, shifted_bound, p, b, floor, dl);
}

namespace {

double first_crossing(const Wave& f, Bounds& bound, const Point& p, double b, double floor, Deadline& dl) {
  // Far from a root the whole search is skipped: f >= f(a) + f'(a) s - max|f''| s^2 / 2,
  // and when that stays clear of f's rounding (relative to its terms) up to b, no
  // evaluation on (a, b] can come out <= 0. Every contact is searched at every event, and
  // most are far from closing or detaching.
  const double h = b - p.t;
  const double low = p.f + std::min(0.0, p.df * h) - 0.5 * bound(p.t, 2) * h * h;
  if (low > 1e-10 * (std::abs(f.f0) + 2.0 * bound(f.t0, 0))) return kNaN;
  return crossing(f, bound, p, b, floor, dl);
}

// The first crossing after p, where f(p) > 0.
// How far past p (f(p) > 0) f stays positive by its Taylor bound alone: f(p + s) >= f(p) +
// f'(p) s - d2 s^2 / 2 (d2 >= |f''| from p on), positive below that quadratic's root. Taken
// at 0.9 of it, so the bound is positive by a tenth of its reach there.
double reach(const Point& p, double d2) {
  if (!(d2 > 0.0)) return p.df >= 0.0 ? std::numeric_limits<double>::infinity() : -0.9 * p.f / p.df;
  const double disc = std::sqrt(p.df * p.df + 2.0 * d2 * p.f);
  // The root (f' + disc) / d2, written without cancellation when f' < 0.
  return 0.9 * (p.df >= 0.0 ? (p.df + disc) / d2 : 2.0 * p.f / (disc - p.df));
}

double crossing(const Wave& f, Bounds& bound, Point p, double b, double floor, Deadline& dl) {
  const double mean = f.mean();
  while (p.t < b) {
    tick(dl);
    if (mean - bound(p.t, 0) > 0.0) return kNaN;
    const double h = std::max(window(bound, p.t, p.f, b - p.t), std::min(floor, b - p.t));
    // A gap that has just opened (f(p) tiny, f'(p) > 0) gets Hermite windows as short as its
    // value allows, which grow only like f^(1/4): several evaluations to leave zero. The
    // Taylor bound proves more of them root-free at once; the next window starts there.
    const double far = reach(p, bound(p.t, 2));
    if (far > h) {
      if (far >= b - p.t) return kNaN;
      const Point q = at(f, p.t + far);
      if (q.f > 0.0) {
        p = q;
        continue;
      }
      return search(f, bound, p, q, floor, dl);  // rounding below zero where the bound is not
    }
    const double tb = h >= b - p.t ? b : p.t + h;
    const Point q = at(f, tb);
    const double r = search(f, bound, p, q, floor, dl);
    if (!std::isnan(r)) return r;
    p = q;
  }
  return kNaN;
}

}  // namespace

namespace {

// Zero of f' between a and b where f' changes sign and f'' has one sign: the
// root polish above on s f' (s making it positive at a), each step one evaluation of f, f',
// f''. Of the last bracket's two ends, the one of smaller |f'|, as before.
//
// It replaces Newton-bisection that evaluated f twice a step (f'' at the bracket's middle,
// then f' at the Newton point) down to a bracket of 2 eps |t|. The value |f| it leaves
// differs from the old one only by f's rounding between points a few ulps apart (f' is zero
// there, so the motion itself moves by (ulp t)^2 f'' / 2, far below an ulp of f).
struct Slope {
  double t, f, df;  // t, s f'(t), s f''(t)
  double value;     // f(t)
};

Point stationary(const Wave& f, const Point& a, const Point& b) {
  const double s = a.df > 0.0 ? 1.0 : -1.0;
  const Bracket<Slope> end = polish(
      [&](double t) {
        double v[3];
        f.eval(t, v, 3);
        return Slope{t, s * v[1], s * v[2], v[0]};
      },
      Slope{a.t, s * a.df, s * a.ddf, a.f}, Slope{b.t, s * b.df, s * b.ddf, b.f});
  const Slope& best = std::abs(end.lo.f) < std::abs(end.hi.f) ? end.lo : end.hi;
  return {best.t, best.value, s * best.f};
}

// What a peak search maximises. OneSide: |f| (kAbs), f (kUp) or -f (kDown), into one Peak;
// BothSides: f and -f at once, into two (how far a relative displacement goes either way: a
// separation, event_driven.hpp), where a window is skipped only when neither side can hold a
// larger value, for about the cost of one search rather than two. With kAbs the tests are
// max_abs's own, so its arithmetic, and every Pi1 it gives, is what it was.
//
// `quiet` is f's rounding: while every value seen is exactly zero (a peak's value 0), a window
// is excluded against it instead, as a value within f's rounding of zero is no peak to
// locate. Against 0 nothing can be excluded, and a plateau of rounded zeros was halved down
// to the floor everywhere (32 768 windows on the wave max_abs describes). Where a value is
// nonzero, the peak's value is, from the first window on: the tests are the old ones.
enum Side { kAbs, kUp, kDown };

template <Side S>
class OneSide {
 public:
  explicit OneSide(Peak& peak) : peak_(peak) {}
  static double value(double f) { return S == kAbs ? std::abs(f) : S == kUp ? f : -f; }
  void consider(const Point& p) {
    if (value(p.f) > peak_.value) {
      peak_.value = value(p.f);
      peak_.t = p.t;
    }
  }
  // Whether no value of a window whose values lie in [lo - err, hi + err] can beat the peak.
  bool excluded(double lo, double hi, double err, double quiet) const {
    const double top = S == kAbs ? std::max(-lo, hi) : S == kUp ? hi : -lo;
    return top + err <= (peak_.value > 0.0 ? peak_.value : quiet);
  }
  // Whether f, within mean +- swing from here on, can beat the peak no more.
  bool done(double mean, double swing) const { return value_of_mean(mean) + swing <= peak_.value; }
  double scale() const { return peak_.value; }

 private:
  static double value_of_mean(double mean) { return S == kAbs ? std::abs(mean) : value(mean); }
  Peak& peak_;
};

class BothSides {
 public:
  BothSides(Peak& up, Peak& down) : up_(up), down_(down) {}
  void consider(const Point& p) {
    up_.consider(p);
    down_.consider(p);
  }
  bool excluded(double lo, double hi, double err, double quiet) const {
    return up_.excluded(lo, hi, err, quiet) && down_.excluded(lo, hi, err, quiet);
  }
  bool done(double mean, double swing) const { return up_.done(mean, swing) && down_.done(mean, swing); }
  double scale() const { return std::max(up_.scale(), down_.scale()); }

 private:
  OneSide<kUp> up_;
  OneSide<kDown> down_;
};

template <class Target>
void peak_search(const Wave& f, Bounds& bound, const Point& a, const Point& b, double floor, double quiet,
                 Target& target, Deadline& dl) {
  tick(dl);
  const double h = b.t - a.t;
  const Cubic cubic(a, b);
  double lo, hi;
  cubic.range(lo, hi);
  const double err = hermite_error(bound, a.t, h);
  if (target.excluded(lo, hi, err, quiet)) return;
  if (h <= floor) return;
  edge_range(cubic, err, lo, hi);
  if (target.excluded(lo, hi, 0.0, quiet)) return;
  // f monotone: the ends, already considered, hold the max.
  if (one_sign(a.df, b.df, bound(a.t, 2), h)) return;
  // f'' of one sign on the window: exactly one stationary point inside.
  if ((a.df > 0.0) != (b.df > 0.0) && one_sign(a.ddf, b.ddf, bound(a.t, 3), h)) {
    target.consider(stationary(f, a, b));
    return;
  }
  const Point m = at3(f, 0.5 * (a.t + b.t));
  target.consider(m);
  peak_search(f, bound, a, m, floor, quiet, target, dl);
  peak_search(f, bound, m, b, floor, quiet, target, dl);
}

template <class Target>
void max_over(const Wave& f, double a, double b, double floor, Target& target, Deadline& dl) {
  Point p = at3(f, a);
  Bounds bound(f);
  check_finite(bound, p);
  target.consider(p);
  const double mean = f.mean();
  const double quiet = 8.0 * std::numeric_limits<double>::epsilon() * (std::abs(mean) + bound(a, 0));
  while (p.t < b) {
    tick(dl);
    if (target.done(mean, bound(p.t, 0))) return;
    const double ref = std::max(target.scale(), std::abs(p.f));
    // Nothing found yet and f rounding to exactly zero: the window rule has no value to scale
    // with (it gives 0, the floor), so the window doubles the distance from a, as first_root
    // walks off a zero gap. Undamped body 0 at Pi2 = 2^k from rest is such a wave: the free
    // term's amplitude is the forced one's over 2^k, exactly in binary, and their sines cancel
    // to exact zeros up to t ~ 5e-9 T_p; at the floor (1e-13 t_min) that plateau took 33 551
    // windows, 4.3 ms for the case against 0.15 ms at Pi2 = 4.00005. Where the second
    // point's value is nonzero the windows are the old ones: on the paper set all but two
    // points' (their Pi1 moved by 1e-15), on the stress set all.
    const double h = ref > 0.0 ? std::max(window(bound, p.t, ref, b - p.t), std::min(floor, b - p.t))
                               : std::min(std::max(floor, p.t - a), b - p.t);
    const Point q = at3(f, h >= b - p.t ? b : p.t + h);
    target.consider(q);
    peak_search(f, bound, p, q, floor, quiet, target, dl);
    p = q;
  }
}

}  // namespace

void max_abs(const Wave& f, double a, double b, double floor, Peak& peak, Deadline& dl) {
  OneSide<kAbs> target(peak);
  max_over(f, a, b, floor, target, dl);
}

void max_both(const Wave& f, double a, double b, double floor, Peak& up, Peak& down, Deadline& dl) {
  BothSides target(up, down);
  max_over(f, a, b, floor, target, dl);
}

namespace detail {

double polish_root(const Wave& f, double lo, double hi) { return refine_root(f, at(f, lo), at(f, hi)); }

Peak polish_stationary(const Wave& f, double a, double b) {
  const Point p = stationary(f, at3(f, a), at3(f, b));
  return {std::abs(p.f), p.t};
}

}  // namespace detail

}  // namespace pb::event_driven
