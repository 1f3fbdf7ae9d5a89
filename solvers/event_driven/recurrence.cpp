#include "solvers/event_driven/recurrence.hpp"

#include <algorithm>

namespace pb::event_driven {

Recurrence::Recurrence(double m, double c, double k) {
  two_sigma_ = c / m;
  w2_ = k / m;
  w_ = std::sqrt(w2_);
  inv_w2_ = 1.0 / w2_;
  inv_w_ = 1.0 / w_;
  by_slot_.reserve(Lengths::kMax);  // allocated here, never in a step
  valid_ = m > 0.0 && c >= 0.0 && k > 0.0 && std::isfinite(two_sigma_) && std::isfinite(w2_) &&
           std::isfinite(inv_w2_) && std::isfinite(inv_w_);
}

namespace recurrence_series {

using Mat2 = std::array<std::array<long double, 2>, 2>;
using Vec2 = std::array<long double, 2>;

Mat2 product(const Mat2& a, const Mat2& b) {
  return {{{a[0][0] * b[0][0] + a[0][1] * b[1][0], a[0][0] * b[0][1] + a[0][1] * b[1][1]},
           {a[1][0] * b[0][0] + a[1][1] * b[1][0], a[1][0] * b[0][1] + a[1][1] * b[1][1]}}};
}

Vec2 mat_vec(const Mat2& a, const Vec2& x) { return {a[0][0] * x[0] + a[0][1] * x[1], a[1][0] * x[0] + a[1][1] * x[1]}; }

}  // namespace recurrence_series

Transition transition(double two_sigma, double w2, double h) {
  using recurrence_series::Mat2;
  using recurrence_series::Vec2;
  using recurrence_series::mat_vec;
  using recurrence_series::product;
  // In the balanced state z = (w x, v), z' = K z + e2 q with K = [[0, w], [-w, -2 sigma]]: every
  // entry of K is w or 2 sigma, so the series and squarings below see no scale between the
  // units of x and v. Over a step of length s, with X = K s,
  //   z(s) - z(0) = E z(0) + G1 e2 q0 + G2 e2 q1,  E = exp(X) - I,
  //   G1 = integral_0^s exp(K (s - r)) dr,  G2 = integral_0^s exp(K (s - r)) r dr
  // (s phi_1(X) and s^2 phi_2(X)): E from its Taylor series, never I plus a small matrix, and
  // of G1, G2 only their second columns (the load enters v alone).
  const long double w = std::sqrt(static_cast<long double>(w2)), ts = two_sigma;
  // Halved until |X| <= 1/2, where 24 terms leave nothing a long double holds; then doubled
  // back: E(2s) = 2 E + E^2, G1(2s) = (2 I + E) G1, G2(2s) = (2 I + E) G2 + s G1.
  long double s = h;
  int halvings = 0;
  while ((2.0L * w + ts) * s > 0.5L && halvings < 64) {
    s *= 0.5L;
    ++halvings;
  }
  const Mat2 x{{{0.0L, w * s}, {-w * s, -ts * s}}};
  Mat2 e{}, power{{{1.0L, 0.0L}, {0.0L, 1.0L}}};
  Vec2 g1{0.0L, s}, g2{0.0L, 0.5L * s * s};  // the j = 0 terms: s e2 / 1!, s^2 e2 / 2!
  long double inv = 1.0L;                     // 1 / j!
  for (int j = 1; j <= 24; ++j) {
    power = product(power, x);
    inv /= static_cast<long double>(j);
    const long double c1 = inv / static_cast<long double>(j + 1), c2 = c1 / static_cast<long double>(j + 2);
    for (std::size_t r = 0; r < 2; ++r) {
      for (std::size_t c = 0; c < 2; ++c) e[r][c] += power[r][c] * inv;
      g1[r] += power[r][1] * c1 * s;
      g2[r] += power[r][1] * c2 * s * s;
    }
  }
  for (int k = 0; k < halvings; ++k) {
    Mat2 twice = e;  // 2 I + E
    twice[0][0] += 2.0L;
    twice[1][1] += 2.0L;
    const Vec2 g1_twice = mat_vec(twice, g1), g2_twice = mat_vec(twice, g2);
    g2 = {g2_twice[0] + s * g1[0], g2_twice[1] + s * g1[1]};
    g1 = g1_twice;
    const Mat2 sq = product(e, e);
    for (std::size_t r = 0; r < 2; ++r)
      for (std::size_t c = 0; c < 2; ++c) e[r][c] = 2.0L * e[r][c] + sq[r][c];
    s *= 2.0L;
  }
  // Back to x = z0 / w: dx = E00 x0 + E01 v0 / w + G1_0 q0 / w + G2_0 q1 / w,
  // dv = E10 w x0 + E11 v0 + G1_1 q0 + G2_1 q1.
  Transition t;
  t.h = h;
  t.d[0][0] = static_cast<double>(e[0][0]);
  t.d[0][1] = static_cast<double>(e[0][1] / w);
  t.d[0][2] = static_cast<double>(g1[0] / w);
  t.d[0][3] = static_cast<double>(g2[0] / w);
  t.d[1][0] = static_cast<double>(e[1][0] * w);
  t.d[1][1] = static_cast<double>(e[1][1]);
  t.d[1][2] = static_cast<double>(g1[1]);
  t.d[1][3] = static_cast<double>(g2[1]);
  return t;
}

}  // namespace pb::event_driven
