#include "solvers/event_driven/impact.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kit/lcp/small.hpp"

namespace pb::event_driven {

double gap_rate(const System& s, int j, std::span<const double> v) { return s.gap_rate(j, v.data()); }

namespace {

// Relative rounding of a rate computed from velocities (a few hundred ulps of margin).
constexpr double kRoundOff = 1e-13;

double inv_mass(const System& s, int body) { return 1.0 / s.bodies[static_cast<std::size_t>(body)].m; }

// (W^T M^-1 W)_{jj}: 1/m_left + 1/m_right (the wall is immovable).
double delassus_diagonal(const System& s, int j) {
  const int l = s.left(j);
  return l == kWall ? inv_mass(s, s.right(j)) : inv_mass(s, l) + inv_mass(s, s.right(j));
}

// (W^T M^-1 W)_{jk}, j < k: -1/m of the body they share, or 0.
double delassus_off(const System& s, int j, int k) {
  return s.right(j) == s.left(k) ? -inv_mass(s, s.right(j)) : 0.0;
}

void apply(const System& s, int j, double impulse, std::span<double> v) {
  const int l = s.left(j), r = s.right(j);
  v[static_cast<std::size_t>(r)] += impulse / s.bodies[static_cast<std::size_t>(r)].m;
  if (l != kWall) v[static_cast<std::size_t>(l)] -= impulse / s.bodies[static_cast<std::size_t>(l)].m;
}

// z_J = -(G_JJ)^-1 q_J for the contacts J flagged in work.in, z = 0 elsewhere: the
// Thomas algorithm on each stretch of consecutive flagged contacts.
void solve_on(const Eigen::VectorXd& q, Eigen::VectorXd& z, ImpactWork& work) {
  const Eigen::Index n = q.size();
  for (Eigen::Index a = 0; a < n; ++a) {
    if (!work.in[static_cast<std::size_t>(a)]) {
      z(a) = 0.0;
    } else if (a > 0 && work.in[static_cast<std::size_t>(a - 1)]) {
      const double f = work.off(a - 1) / work.pivot(a - 1);
      work.pivot(a) = work.main(a) - f * work.off(a - 1);
      z(a) = -q(a) - f * z(a - 1);
    } else {
      work.pivot(a) = work.main(a);
      z(a) = -q(a);
    }
  }
  for (Eigen::Index a = n - 1; a >= 0; --a) {
    if (!work.in[static_cast<std::size_t>(a)]) continue;
    if (a + 1 < n && work.in[static_cast<std::size_t>(a + 1)]) z(a) -= work.off(a) * z(a + 1);
    z(a) /= work.pivot(a);
  }
}

// LCP(G, q) for the tridiagonal G (diagonal work.main, off-diagonal work.off) of a run, by
// Chandrasekaran's method for M-matrices (G is one: positive definite, off-diagonal <= 0,
// so G^-1 >= 0): solve w_J = 0 on a set J of contacts, add every contact outside J whose
// w is then negative, repeat. As long as J lies within the solution's {w = 0}, z_J stays
// >= 0 and J only grows, so it ends within n steps, exact like any active-set method; each
// step is O(n). The start J = {q <= 0} does lie there (G^-1 >= 0: a contact with q <= 0
// either pushes or is pushed shut by its neighbours), and is usually the answer at once:
// a blow on a chain at rest in contact reaches every contact in one step, where starting
// from {q < 0} would creep along the chain one contact per step. Rates within `noise` of
// zero are rounding (contacts at rest relative to each other) and are taken as zero.
// False if rounding broke the sign of z.
bool chandrasekaran(const Eigen::VectorXd& q_in, double noise, Eigen::VectorXd& z, ImpactWork& work) {
  const Eigen::Index n = q_in.size();
  work.pivot.resize(n);
  work.q.resize(n);
  work.in.resize(static_cast<std::size_t>(n));
  for (Eigen::Index a = 0; a < n; ++a) {
    work.q(a) = std::abs(q_in(a)) <= noise ? 0.0 : q_in(a);
    work.in[static_cast<std::size_t>(a)] = work.q(a) <= 0.0 ? 1 : 0;
  }
  const Eigen::VectorXd& q = work.q;
  for (Eigen::Index step = 0; step <= n; ++step) {
    solve_on(q, z, work);
    bool added = false;
    for (Eigen::Index a = 0; a < n; ++a) {
      if (work.in[static_cast<std::size_t>(a)]) continue;
      double w = q(a);
      if (a > 0) w += work.off(a - 1) * z(a - 1);
      if (a + 1 < n) w += work.off(a) * z(a + 1);
      if (w < -noise) {
        work.in[static_cast<std::size_t>(a)] = 1;
        added = true;
      }
    }
    if (!added) return (z.array() >= 0.0).all();
  }
  return false;
}

// LCP(G, q) of a run: Chandrasekaran's method, and Lemke's (O(n^2) per pivot, on the dense
// G) should it fail, or alone when work.lemke_only.
void solve_lcp(const Eigen::VectorXd& q, double noise, Eigen::VectorXd& z, ImpactWork& work, const char* what) {
  if (!work.lemke_only && chandrasekaran(q, noise, z, work)) return;
  const Eigen::Index n = q.size();
  work.g.setZero(n, n);
  work.g.diagonal() = work.main;
  work.g.diagonal(1) = work.off;
  work.g.diagonal(-1) = work.off;
  const lcp::LemkeResult r = lcp::lemke(work.g, q, z, work.lemke);
  if (r.status != lcp::Status::solved)
    throw std::runtime_error(std::string("Poisson impact: Lemke's method ended with ") +
                             std::string(lcp::name(r.status)) + " on the " + what + " LCP of " +
                             std::to_string(n) + " contacts");
}

// y = G x for the tridiagonal G of work.
void multiply(const ImpactWork& work, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const Eigen::Index n = x.size();
  for (Eigen::Index a = 0; a < n; ++a) {
    double v = work.main(a) * x(a);
    if (a > 0) v += work.off(a - 1) * x(a - 1);
    if (a + 1 < n) v += work.off(a) * x(a + 1);
    y(a) = v;
  }
}

}  // namespace

void poisson_run(const System& s, std::span<const int> run, std::span<double> v, double eps, ImpactWork& work,
                 std::span<double> impulse) {
  const std::size_t n = run.size();
  if (n == 1) {
    const int j = run[0];
    const double g = delassus_diagonal(s, j);
    const double gd_a = gap_rate(s, j, v);
    const double lc = lcp::solve1(g, gd_a);
    const double gd_c = g * lc + gd_a;
    const double lp = lcp::solve1(g, gd_c + eps * g * lc);
    impulse[0] = (1.0 + eps) * lc + lp;
  } else if (n == 2) {
    Eigen::Matrix2d g;
    g << delassus_diagonal(s, run[0]), delassus_off(s, run[0], run[1]), delassus_off(s, run[0], run[1]),
        delassus_diagonal(s, run[1]);
    const Eigen::Vector2d gd_a(gap_rate(s, run[0], v), gap_rate(s, run[1], v));
    const Eigen::Vector2d lc = lcp::solve2(g, gd_a);
    const Eigen::Vector2d gd_c = g * lc + gd_a;
    const Eigen::Vector2d lp = lcp::solve2(g, gd_c + eps * (g * lc));
    const Eigen::Vector2d total = (1.0 + eps) * lc + lp;
    impulse[0] = total(0);
    impulse[1] = total(1);
  } else if (n > 2) {
    const auto m = static_cast<Eigen::Index>(n);
    work.main.resize(m);
    work.off.resize(m - 1);
    work.gd.resize(m);
    work.rhs.resize(m);
    work.lc.resize(m);
    work.lp.resize(m);
    double speed = 0.0;  // of the run's bodies: what the rates' rounding is relative to
    for (Eigen::Index a = 0; a < m; ++a) {
      const int j = run[static_cast<std::size_t>(a)];
      work.main(a) = delassus_diagonal(s, j);
      if (a > 0) work.off(a - 1) = delassus_off(s, run[static_cast<std::size_t>(a - 1)], j);
      work.gd(a) = gap_rate(s, j, v);
      speed = std::max(speed, std::abs(v[static_cast<std::size_t>(s.right(j))]));
      if (s.left(j) != kWall) speed = std::max(speed, std::abs(v[static_cast<std::size_t>(s.left(j))]));
    }
    const double noise = kRoundOff * speed;
    solve_lcp(work.gd, noise, work.lc, work, "compression");
    multiply(work, work.lc, work.rhs);  // G Lambda_C; gd_C = G Lambda_C + gd_A
    work.rhs = (1.0 + eps) * work.rhs + work.gd;
    solve_lcp(work.rhs, noise, work.lp, work, "expansion");
    for (Eigen::Index a = 0; a < m; ++a)
      impulse[static_cast<std::size_t>(a)] = (1.0 + eps) * work.lc(a) + work.lp(a);
  }
  for (std::size_t a = 0; a < n; ++a) apply(s, run[a], impulse[a], v);
}

ImpactOutcome poisson_impact(const System& s, std::span<const int> set, std::span<double> v, double eps) {
  ImpactOutcome out;
  out.impulse.assign(set.size(), 0.0);
  out.gap_rate.assign(set.size(), 0.0);
  ImpactWork work;
  for_each_run(s, set, [&](std::size_t begin, std::size_t end) {
    poisson_run(s, set.subspan(begin, end - begin), v, eps, work,
                std::span<double>(out.impulse).subspan(begin, end - begin));
  });
  for (std::size_t a = 0; a < set.size(); ++a) out.gap_rate[a] = gap_rate(s, set[a], v);
  return out;
}

}  // namespace pb::event_driven
