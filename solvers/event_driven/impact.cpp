#include "solvers/event_driven/impact.hpp"

#include <stdexcept>

#include "solvers/lcp/small.hpp"

namespace pb::event_driven {

double gap_rate(const System& s, int j, std::span<const double> v) {
  const int l = s.left(j), r = s.right(j);
  return v[static_cast<std::size_t>(r)] - (l == kWall ? 0.0 : v[static_cast<std::size_t>(l)]);
}

namespace {

// (W^T M^-1 W)_{jk} for contacts j, k of a row.
double delassus(const System& s, int j, int k) {
  double g = 0.0;
  auto coef = [](int body, int l, int r) { return body == r ? 1.0 : body == l ? -1.0 : 0.0; };
  for (int i = 0; i < s.n_bodies(); ++i) {
    const double wj = coef(i, s.left(j), s.right(j)), wk = coef(i, s.left(k), s.right(k));
    if (wj != 0.0 && wk != 0.0) g += wj * wk / s.bodies[static_cast<std::size_t>(i)].m;
  }
  return g;
}

void apply(const System& s, int j, double impulse, std::span<double> v) {
  const int l = s.left(j), r = s.right(j);
  v[static_cast<std::size_t>(r)] += impulse / s.bodies[static_cast<std::size_t>(r)].m;
  if (l != kWall) v[static_cast<std::size_t>(l)] -= impulse / s.bodies[static_cast<std::size_t>(l)].m;
}

}  // namespace

ImpactOutcome poisson_impact(const System& s, std::span<const int> set, std::span<double> v, double eps) {
  ImpactOutcome out;
  const std::size_t n = set.size();
  out.impulse.assign(n, 0.0);
  out.gap_rate.assign(n, 0.0);
  if (n == 1) {
    const int j = set[0];
    const double g = delassus(s, j, j);
    const double gd_a = gap_rate(s, j, v);
    const double lc = lcp::solve1(g, gd_a);
    const double gd_c = g * lc + gd_a;
    const double lp = lcp::solve1(g, gd_c + eps * g * lc);
    out.impulse[0] = (1.0 + eps) * lc + lp;
  } else if (n == 2) {
    Eigen::Matrix2d g;
    Eigen::Vector2d gd_a;
    for (std::size_t a = 0; a < 2; ++a) {
      gd_a(static_cast<Eigen::Index>(a)) = gap_rate(s, set[a], v);
      for (std::size_t b = 0; b < 2; ++b)
        g(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) = delassus(s, set[a], set[b]);
    }
    const Eigen::Vector2d lc = lcp::solve2(g, gd_a);
    const Eigen::Vector2d gd_c = g * lc + gd_a;
    const Eigen::Vector2d lp = lcp::solve2(g, gd_c + eps * (g * lc));
    const Eigen::Vector2d total = (1.0 + eps) * lc + lp;
    out.impulse = {total(0), total(1)};
  } else if (n > 2) {
    throw std::invalid_argument("poisson_impact: more than two simultaneous contacts");
  }
  for (std::size_t a = 0; a < n; ++a) apply(s, set[a], out.impulse[a], v);
  for (std::size_t a = 0; a < n; ++a) out.gap_rate[a] = gap_rate(s, set[a], v);
  return out;
}

}  // namespace pb::event_driven
