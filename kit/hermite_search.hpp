#pragma once
// What both exact references' event searches share (solvers/event_driven/search.cpp for the
// single oscillators, solvers/buildings_reference/search.cpp for the buildings): the cubic
// Hermite interpolant of a window and the range of its values, the range with its error bound
// at the ends, the neighbouring doubles, and the polish of a root to adjacent doubles. Each
// search keeps its own evaluation of the motion (a Wave, a Track) and its bounds on it.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace pb::hermite {

// The cubic Hermite interpolant on s in [0, 1] of a window from a to b, each a point with t,
// f and df.
struct Cubic {
  double c0, c1, c2, c3;
  template <class P>
  Cubic(const P& a, const P& b) {
    const double h = b.t - a.t;
    c0 = a.f;
    c1 = h * a.df;
    c2 = 3.0 * (b.f - a.f) - h * (2.0 * a.df + b.df);
    c3 = 2.0 * (a.f - b.f) + h * (a.df + b.df);
  }
  double operator()(double s) const { return c0 + s * (c1 + s * (c2 + s * c3)); }
  // Min and max over [0, 1]: the ends and the stationary points inside.
  void range(double& lo, double& hi) const { range(0.0, 1.0, lo, hi); }
  // The same over [s0, s1].
  void range(double s0, double s1, double& lo, double& hi) const {
    const double v0 = (*this)(s0), v1 = (*this)(s1);
    lo = std::min(v0, v1);
    hi = std::max(v0, v1);
    auto visit = [&](double s) {
      if (s > s0 && s < s1) {
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

// Bounds of f on a window from its interpolant H where the plain ones, H -+ mid (mid the
// error bound hermite_error, at the window's middle), do not settle a test. The error is
// at most max|f''''| (t - a)^2 (b - t)^2 / 24 = 16 mid s^2 (1 - s)^2, which vanishes at
// the ends; on the left half it is at most 16 mid s^2, on the right 16 mid (1 - s)^2, and
// H plus or minus either is a cubic. With the constant bound, a window that ends on the
// largest |f| so far (a peak search's rising f) or near zero (an approaching gap) could
// never be excluded, only halved until f' alone settled it: some 40 halvings in a first
// segment from rest, where f' starts at zero.
inline void edge_range(const Cubic& h, double mid, double& lo, double& hi) {
  const double e = 16.0 * mid;
  double l, u, unused;
  Cubic c = h;
  c.c2 = h.c2 + e;  // H + e s^2
  c.range(0.0, 0.5, unused, u);
  hi = u;
  c.c2 = h.c2 - e;  // H - e s^2
  c.range(0.0, 0.5, l, unused);
  lo = l;
  c.c0 = h.c0 + e;  // H + e (1 - s)^2
  c.c1 = h.c1 - 2.0 * e;
  c.c2 = h.c2 + e;
  c.range(0.5, 1.0, unused, u);
  hi = std::max(hi, u);
  c.c0 = h.c0 - e;  // H - e (1 - s)^2
  c.c1 = h.c1 + 2.0 * e;
  c.c2 = h.c2 - e;
  c.range(0.5, 1.0, l, unused);
  lo = std::min(lo, l);
}

// std::nextafter(x, +inf) and (x, -inf) for a finite x, the same values inline: the polish
// asks for them at every step, and libm's calls were 2 % of the reference's instructions.
inline double next_up(double x) {
  if (x == 0.0) return std::numeric_limits<double>::denorm_min();
  const auto bits = std::bit_cast<std::uint64_t>(x);
  return std::bit_cast<double>(x > 0.0 ? bits + 1 : bits - 1);
}
inline double next_down(double x) { return -next_up(-x); }

// The zero of a function g on a bracket lo < hi with g(lo) > 0 >= g(hi), g monotone there:
// Newton steps from the latest point, each one evaluation, safeguarded by the bracket
// (rtsafe: a step that leaves it, or does not halve the step before last, bisects). Once
// Newton stalls within an ulp of a point (its fixed point), a one-ulp probe beside it
// checks the sign change there. Stops when lo and hi are adjacent doubles and returns hi:
// a double t with g(t) <= 0 < g(t's predecessor), a sign change of g's rounded values.
//
// The polish this replaces (Newton from the end of smaller |g|, bisection whenever Newton
// stalled, down to a bracket of 2 eps |t|) took 21 evaluations a root: Newton from one side
// converges to a point whose next step stays there, and the other end came by halving.
// Its answer was the hi end of that bracket. Where g's rounded values change sign once,
// this answer is the same or up to 2 eps |t| (3 ulp) earlier; g is known only to its
// rounding, 4 eps of its terms S, and within 4 eps S / |g'| of the root either search may
// stop at another of its sign changes (solvers/event_driven/search_test.cpp checks both bounds on random
// waves: of its 2000 roots 73 % are the old ones bit for bit, the others earlier).
//
// eval(t) returns a P with t, f = g(t), df = g'(t) (and whatever else a caller keeps);
// lo.df or hi.df may be NaN (not known): Newton starts from the other end then.
template <class P>
struct Bracket {
  P lo, hi;
};

template <class P, class Eval>
Bracket<P> polish(Eval&& eval, P lo, P hi) {
  P p = (std::abs(lo.f) < std::abs(hi.f) || !std::isfinite(hi.df)) ? lo : hi;
  double step = hi.t - lo.t, step_old = step;
  int probes = 0;  // in a row
  for (int it = 0; it < 300 && next_up(lo.t) < hi.t; ++it) {
    double next = p.t - p.f / p.df;  // NaN or inf when p.df is 0 or unknown: bisection below
    const double ulp = next_up(std::abs(p.t)) - std::abs(p.t);
    double taken;
    const bool fixed = std::abs(next - p.t) <= ulp;
    if (fixed && probes < 2) {
      // Newton's fixed point: probe the neighbour of p toward the bracket's other end.
      next = p.t == lo.t ? next_up(lo.t) : next_down(hi.t);
      taken = ulp;
      ++probes;
    } else if (fixed || !(next > lo.t && next < hi.t) || std::abs(2.0 * (next - p.t)) > std::abs(step_old)) {
      // Also after two probes that found no sign change: rounded values flat across many
      // ulps (a grazing root's plateau of exact zeros), which Newton cannot see across.
      probes = 0;
      taken = 0.5 * (hi.t - lo.t);  // out of the bracket, or slower than halving two steps
      next = lo.t + taken;
      if (!(next > lo.t && next < hi.t)) next = next_up(lo.t);
    } else {
      taken = next - p.t;
      probes = 0;
    }
    step_old = step;  // the step before last, for the next look
    step = taken;
    p = eval(next);
    if (p.f > 0.0)
      lo = p;
    else
      hi = p;
  }
  return {lo, hi};
}

}  // namespace pb::hermite
