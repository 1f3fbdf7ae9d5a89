#include "solvers/buildings_reference/search.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "kit/hermite_search.hpp"

namespace pb::buildings {

namespace {

using hermite::Bracket;
using hermite::Cubic;
using hermite::edge_range;
using hermite::next_down;
using hermite::next_up;
using hermite::polish;

constexpr double kNoRoot = std::numeric_limits<double>::quiet_NaN();

struct Point {
  double t, f, df;
  double ddf = std::numeric_limits<double>::quiet_NaN();  // f'', where the peak search needs it
};

Point at(const Track& w, double t) {
  double v[2];
  w.eval(t, v, 2);
  return {t, v[0], v[1]};
}

Point at3(const Track& w, double t) {
  double v[3];
  w.eval(t, v, 3);
  return {t, v[0], v[1], v[2]};
}

// A track's bounds at the last t asked (the searches ask for several orders at one t).
class Bounds {
 public:
  explicit Bounds(const Track& w) : w_(w) {}
  // Known already at t (the peak grid's).
  Bounds(const Track& w, double t, const double* known) : w_(w), t_(t) {
    std::copy(known, known + kMaxOrder + 1, value_);
  }
  double operator()(double t, int d) {
    if (!(t == t_)) {
      w_.bounds(t, value_);
      t_ = t;
    }
    return value_[d];
  }

 private:
  const Track& w_;
  double t_ = std::numeric_limits<double>::quiet_NaN();
  double value_[kMaxOrder + 1] = {};
};

double hermite_error(Bounds& bound, double a, double h) {
  const double h2 = h * h;
  return bound(a, 4) * h2 * h2 / 384.0;
}

double refine_root(const Track& g, const Point& lo, const Point& hi) {
  return polish([&](double t) { return at(g, t); }, lo, hi).hi.t;
}

// Whether y keeps one sign on a window of length h, given y at its ends and a bound d on |y'|.
bool one_sign(double ya, double yb, double d, double h) {
  if (std::abs(ya) > d * h) return true;
  return ya != 0.0 && (ya > 0.0) == (yb > 0.0) && std::abs(ya) + std::abs(yb) > d * h;
}

void tick(Deadline& deadline) {
  if (deadline.tick()) throw OutOfTime{};
}

double search(const Track& g, Bounds& bound, const Point& a, const Point& b, double floor, Deadline& dl) {
  tick(dl);
  const double h = b.t - a.t;
  if (b.f <= 0.0) {
    if (one_sign(a.df, b.df, bound(a.t, 2), h) || h <= floor) return refine_root(g, a, b);
  } else {
    const Cubic cubic(a, b);
    double lo, hi;
    cubic.range(lo, hi);
    if (lo - g.hermite_error(a.t, h) > 0.0) return kNoRoot;
    if (h <= floor) return kNoRoot;  // a touch within round-off, not a contact
    edge_range(cubic, hermite_error(bound, a.t, h), lo, hi);
    if (lo > 0.0) return kNoRoot;
  }
  const Point m = at(g, 0.5 * (a.t + b.t));
  if (m.f <= 0.0) {
    const double r = search(g, bound, a, m, floor, dl);
    return std::isnan(r) ? refine_root(g, a, m) : r;
  }
  const double r = search(g, bound, a, m, floor, dl);
  return std::isnan(r) ? search(g, bound, m, b, floor, dl) : r;
}

// A window whose Hermite error is at most a quarter of |f|: from the fourth derivative's bound,
// then doubled while the mode-by-mode bound (Motion::hermite_error) still allows it.
double window(const Track& g, Bounds& bound, double t, double f, double rest) {
  const double b4 = bound(t, 4);
  if (b4 <= 0.0) return rest;
  double h = std::min(rest, std::sqrt(std::sqrt(96.0 * std::abs(f) / b4)));
  const double target = 0.25 * std::abs(f);
  for (int i = 0; i < 8 && h < rest; ++i) {
    const double longer = std::min(2.0 * h, rest);
    if (!(g.hermite_error(t, longer) <= target)) break;
    h = longer;
  }
  return h;
}

void check_finite(Bounds& bound, const Point& p) {
  if (!std::isfinite(p.f) || !std::isfinite(p.df) || !std::isfinite(bound(p.t, 4))) throw NonFinite{};
}

// How far past p (f(p) > 0) f stays positive by its Taylor bound, at 0.9 of the reach.
double reach(const Point& p, double d2) {
  if (!(d2 > 0.0)) return p.df >= 0.0 ? std::numeric_limits<double>::infinity() : -0.9 * p.f / p.df;
  const double disc = std::sqrt(p.df * p.df + 2.0 * d2 * p.f);
  return 0.9 * (p.df >= 0.0 ? (p.df + disc) / d2 : 2.0 * p.f / (disc - p.df));
}

double crossing(const Track& f, Bounds& bound, Point p, double b, double floor, Deadline& dl) {
  const double mean = f.mean();
  while (p.t < b) {
    tick(dl);
    if (mean - bound(p.t, 0) > 0.0) return kNoRoot;
    const double h = std::max(window(f, bound, p.t, p.f, b - p.t), std::min(floor, b - p.t));
    const double far = reach(p, bound(p.t, 2));
    if (far > h) {
      if (far >= b - p.t) return kNoRoot;
      const Point q = at(f, p.t + far);
      if (q.f > 0.0) {
        p = q;
        continue;
      }
      return search(f, bound, p, q, floor, dl);
    }
    const double tb = h >= b - p.t ? b : p.t + h;
    const Point q = at(f, tb);
    const double r = search(f, bound, p, q, floor, dl);
    if (!std::isnan(r)) return r;
    p = q;
  }
  return kNoRoot;
}

double first_crossing(const Track& f, Bounds& bound, const Point& p, double b, double floor, Deadline& dl) {
  // Far from a root the whole search is skipped: f >= f(a) + f'(a) s - max|f''| s^2 / 2 stays
  // clear of f's rounding up to b.
  const double h = b - p.t;
  const double low = p.f + std::min(0.0, p.df * h) - 0.5 * bound(p.t, 2) * h * h;
  if (low > 1e-10 * (std::abs(f.f0()) + 2.0 * bound(f.t0(), 0))) return kNoRoot;
  return crossing(f, bound, p, b, floor, dl);
}

// The zero of f' between a and b where f' changes sign and f'' has one sign.
struct Slope {
  double t, f, df;  // t, s f'(t), s f''(t)
  double value;     // f(t)
};

Point stationary(const Track& f, const Point& a, const Point& b) {
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

void consider(const Point& p, Peak& peak) {
  if (std::abs(p.f) > peak.value) {
    peak.value = std::abs(p.f);
    peak.t = p.t;
  }
}

// What a peak search raises: the largest |f| (max_abs, the peaks of floors and storeys), or
// the largest f and the largest -f at once (max_both, how far a relative displacement goes
// either way). The |f| target's tests are max_abs's own, so its arithmetic is unchanged.
class AbsTarget {
 public:
  explicit AbsTarget(Peak& peak) : peak_(peak) {}
  void consider(const Point& p) { buildings::consider(p, peak_); }
  // Whether no value of a window whose values lie in [lo - err, hi + err] can beat the peak
  // (`quiet`: f's rounding, the peak while every value seen rounds to zero).
  bool excluded(double lo, double hi, double err, double quiet) const {
    return std::max(-lo, hi) + err <= (peak_.value > 0.0 ? peak_.value : quiet);
  }
  // Whether f, within mean +- swing from here on, can beat the peak no more.
  bool done(double mean, double swing) const { return std::abs(mean) + swing <= peak_.value; }
  double scale() const { return peak_.value; }

 private:
  Peak& peak_;
};

class BothTarget {
 public:
  BothTarget(Peak& up, Peak& down) : up_(up), down_(down) {}
  void consider(const Point& p) {
    if (p.f > up_.value) up_ = {p.f, p.t};
    if (-p.f > down_.value) down_ = {-p.f, p.t};
  }
  bool excluded(double lo, double hi, double err, double quiet) const {
    return hi + err <= (up_.value > 0.0 ? up_.value : quiet) && -lo + err <= (down_.value > 0.0 ? down_.value : quiet);
  }
  bool done(double mean, double swing) const { return mean + swing <= up_.value && -mean + swing <= down_.value; }
  double scale() const { return std::max(up_.value, down_.value); }

 private:
  Peak& up_;
  Peak& down_;
};

// The target by value: it holds references to the peaks it raises.
template <class Target>
void peak_search(const Track& f, Bounds& bound, const Point& a, const Point& b, double floor, double quiet,
                 Target target, Deadline& dl) {
  tick(dl);
  const double h = b.t - a.t;
  const Cubic cubic(a, b);
  double lo, hi;
  cubic.range(lo, hi);
  if (target.excluded(lo, hi, f.hermite_error(a.t, h), quiet)) return;
  if (h <= floor) return;
  edge_range(cubic, hermite_error(bound, a.t, h), lo, hi);
  if (target.excluded(lo, hi, 0.0, quiet)) return;
  if (one_sign(a.df, b.df, bound(a.t, 2), h)) return;  // monotone: the ends hold the max
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
void max_over(const Track& f, double a, double b, double floor, Target& target, Deadline& dl) {
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
    // While everything seen rounds to zero the window doubles its distance from a.
    const double h = ref > 0.0 ? std::max(window(f, bound, p.t, ref, b - p.t), std::min(floor, b - p.t))
                               : std::min(std::max(floor, p.t - a), b - p.t);
    const Point q = at3(f, h >= b - p.t ? b : p.t + h);
    target.consider(q);
    peak_search(f, bound, p, q, floor, quiet, target, dl);
    p = q;
  }
}

}  // namespace

double first_root(const Track& f, double a, double b, double floor, double settle, double noise, Deadline& dl) {
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
  // Neutral: the event is where f first falls below -noise (now, if it already has).
  Track shifted = f;
  shifted.shift += noise;
  p = at(shifted, a);
  if (!(p.f > 0.0)) return a;
  Bounds shifted_bound(shifted);
  return first_crossing(shifted, shifted_bound, p, b, floor, dl);
}

void max_abs(const Track& f, double a, double b, double floor, Peak& peak, Deadline& dl) {
  AbsTarget target(peak);
  max_over(f, a, b, floor, target, dl);
}

void max_both(const Track& f, double a, double b, double floor, Peak& up, Peak& down, Deadline& dl) {
  BothTarget target(up, down);
  max_over(f, a, b, floor, target, dl);
}

void PeakSearch::reserve(int quantities) {
  const auto n = static_cast<std::size_t>(quantities);
  for (std::vector<double>* v : {&mean_, &quiet_}) v->resize(n);
  active_.resize(n);
  grid_.resize(kChunk + 1);
  values_.resize(3 * n * (kChunk + 1));
  bounds_.resize((kMaxOrder + 1) * n * (kChunk + 1));
}

void PeakSearch::run(Motion& m, const int* qs, Peak* peaks, int n, double a, double b, double floor, Deadline& dl) {
  const auto count = static_cast<std::size_t>(n);
  double bd[kMaxOrder + 1];
  bool presample = false;
  // values_: per grid point k, per quantity i, (f, f', f'') at 3 (k n + i).
  const auto put = [&](std::size_t k, double t) {
    grid_[k] = t;
    for (std::size_t i = 0; i < count; ++i) {
      if (!active_[i]) continue;
      double* out = &values_[3 * (k * count + i)];
      m.eval(qs[i], t, out, 3);
      if (!std::isfinite(out[0]) || !std::isfinite(out[1])) throw NonFinite{};
      consider(Point{t, out[0], out[1], out[2]}, peaks[i]);
    }
  };
  int left = 0;
  for (std::size_t i = 0; i < count; ++i) {
    mean_[i] = std::abs(m.mean(qs[i]));
    m.bounds(qs[i], a, bd);
    if (!std::isfinite(bd[kMaxOrder])) throw NonFinite{};
    quiet_[i] = 8.0 * std::numeric_limits<double>::epsilon() * (mean_[i] + bd[0]);
    // Not searched where it cannot beat its peak: |f| <= |f(a)| + |f'(a)| s + max|f''| s^2 / 2
    // (most quantities over the short segments between impacts), or its swing about its mean.
    const double h = b - a, f0 = m.f0(qs[i]);
    const double taylor = std::abs(f0) + std::abs(m.rate0(qs[i])) * h + 0.5 * bd[2] * h * h;
    consider(Point{a, f0, m.rate0(qs[i])}, peaks[i]);
    active_[i] = !(std::min(taylor, mean_[i] + bd[0]) <= peaks[i].value);
    if (active_[i]) {
      ++left;
      if (peaks[i].value < kPresample * (mean_[i] + bd[0])) presample = true;
    }
  }
  if (left == 0) return;
  // A quantity whose peak so far is far below what it may reach here (the rise from rest)
  // asks for windows as short as its peak is small, and would set the grid for all: its peak
  // is first raised to the values at evenly spaced points, two per radian of the fastest
  // rate (true values, which any window is then tested against).
  if (presample) {
    const double span = b - a;
    const int points = std::min(kMaxPresample, static_cast<int>(std::ceil(0.5 * span * m.fastest())));
    double out[1];
    for (int p = 1; p <= points; ++p) {
      const double t = a + span * p / (points + 1);
      for (std::size_t i = 0; i < count; ++i) {
        if (!active_[i]) continue;
        m.eval(qs[i], t, out, 1);
        if (std::abs(out[0]) > peaks[i].value) peaks[i] = {std::abs(out[0]), t};
      }
    }
  }
  put(0, a);
  while (grid_[0] < b && left > 0) {
    // Pass 1: up to kChunk windows, each the shortest any active quantity asks for (max_abs's
    // rule), every quantity evaluated at its end from one basis, its peak raised to the values.
    std::size_t k = 0;
    while (k < kChunk && grid_[k] < b) {
      tick(dl);
      const double t = grid_[k];
      double h = b - t;
      for (std::size_t i = 0; i < count; ++i) {
        if (!active_[i]) continue;
        double* known = &bounds_[(kMaxOrder + 1) * (k * count + i)];
        m.bounds(qs[i], t, known);
        const double f = values_[3 * (k * count + i)];
        const double ref = std::max(peaks[i].value, std::abs(f));
        const Track track{&m, qs[i], 0.0};
        Bounds bound(track, t, known);
        // The shortest window yet needs no longer a search than it.
        const double rest = std::min(h, b - t);
        const double hi = ref > 0.0 ? std::max(window(track, bound, t, ref, rest), std::min(floor, b - t))
                                    : std::min(std::max(floor, t - a), b - t);
        h = std::min(h, hi);
      }
      put(k + 1, h >= b - t ? b : t + h);
      ++k;
    }
    // Pass 2: each window searched against the peak every value of the chunk has raised.
    for (std::size_t i = 0; i < count; ++i) {
      if (!active_[i]) continue;
      const Track f{&m, qs[i], 0.0};
      for (std::size_t w = 0; w < k; ++w) {
        const double* p0 = &values_[3 * (w * count + i)];
        const double* p1 = &values_[3 * ((w + 1) * count + i)];
        Bounds bound(f, grid_[w], &bounds_[(kMaxOrder + 1) * (w * count + i)]);
        peak_search(f, bound, Point{grid_[w], p0[0], p0[1], p0[2]}, Point{grid_[w + 1], p1[0], p1[1], p1[2]}, floor,
                    quiet_[i], AbsTarget(peaks[i]), dl);
      }
    }
    // The chunk's last point starts the next; a quantity whose bound over the rest of the
    // segment cannot beat its peak leaves.
    grid_[0] = grid_[k];
    for (std::size_t i = 0; i < count; ++i) {
      if (!active_[i]) continue;
      for (int c = 0; c < 3; ++c) values_[3 * i + static_cast<std::size_t>(c)] = values_[3 * (k * count + i) + static_cast<std::size_t>(c)];
      m.bounds(qs[i], grid_[0], bd);
      if (mean_[i] + bd[0] <= peaks[i].value) {
        active_[i] = 0;
        --left;
      }
    }
  }
}

}  // namespace pb::buildings
