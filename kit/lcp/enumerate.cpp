#include "kit/lcp/enumerate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace pb::lcp {

namespace {

constexpr int kMax = kEnumerateMaxSize;
using Square = std::array<std::array<double, kMax>, kMax>;
using Column = std::array<double, kMax>;

// Solves the m x m system s x = b by Gaussian elimination with complete pivoting (the
// backward-stable choice for blocks of any condition); s and b are overwritten. Returns
// false if a pivot falls below threshold times the first (largest) one.
bool solve_block(Square& s, Column& b, int m, double threshold, Column& x) {
  std::array<int, kMax> col{};
  for (int c = 0; c < m; ++c) col[c] = c;
  double first = 0.0;
  for (int k = 0; k < m; ++k) {
    int pr = k, pc = k;
    for (int r = k; r < m; ++r)
      for (int c = k; c < m; ++c)
        if (std::abs(s[r][c]) > std::abs(s[pr][pc])) pr = r, pc = c;
    const double pivot = std::abs(s[pr][pc]);
    if (k == 0) first = pivot;
    if (!(pivot > threshold * first) || pivot == 0.0) return false;
    std::swap(s[k], s[pr]);
    std::swap(b[k], b[pr]);
    if (pc != k) {
      for (int r = 0; r < m; ++r) std::swap(s[r][k], s[r][pc]);
      std::swap(col[k], col[pc]);
    }
    for (int r = k + 1; r < m; ++r) {
      const double f = s[r][k] / s[k][k];
      for (int c = k + 1; c < m; ++c) s[r][c] -= f * s[k][c];
      b[r] -= f * b[k];
    }
  }
  for (int k = m - 1; k >= 0; --k) {
    double v = b[k];
    for (int c = k + 1; c < m; ++c) v -= s[k][c] * b[c];
    b[k] = v / s[k][k];
  }
  for (int k = 0; k < m; ++k) x[col[k]] = b[k];
  return true;
}

}  // namespace

EnumerateResult enumerate(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::VectorXd>& q,
                          const EnumerateSettings& settings) {
  EnumerateResult out;
  const Eigen::Index size = q.size();
  out.z = Eigen::VectorXd::Zero(size);
  if (a.rows() != size || a.cols() != size || size > kMax || !a.allFinite() || !q.allFinite()) {
    out.status = Status::bad_input;
    return out;
  }
  // Plain arrays: this loop runs 2^n times per call, and the tests also run in Debug and
  // sanitizer builds, where per-element Eigen access is slow.
  const int n = static_cast<int>(size);
  Square am{};
  Column qv{};
  double a_norm = 0.0, q_norm = 0.0;
  for (int i = 0; i < n; ++i) {
    double row = 0.0;
    for (int j = 0; j < n; ++j) row += std::abs(am[i][j] = a(i, j));
    a_norm = std::max(a_norm, row);
    q_norm = std::max(q_norm, std::abs(qv[i] = q(i)));
  }

  Square block;
  Column rhs, za, z, best_z{};
  std::array<int, kMax> index{};
  double best = std::numeric_limits<double>::infinity();
  const unsigned sets = 1u << static_cast<unsigned>(n);
  for (unsigned mask = 0; mask < sets; ++mask) {
    int m = 0;
    for (int i = 0; i < n; ++i)
      if (mask & (1u << i)) index[m++] = i;
    for (int r = 0; r < m; ++r) {
      rhs[r] = -qv[index[r]];
      for (int c = 0; c < m; ++c) block[r][c] = am[index[r]][index[c]];
    }
    if (m > 0 && !solve_block(block, rhs, m, settings.pivot_threshold, za)) continue;

    z.fill(0.0);
    double z_norm = 0.0, z_min = 0.0;
    for (int r = 0; r < m; ++r) {
      z[index[r]] = za[r];
      z_norm = std::max(z_norm, std::abs(za[r]));
      z_min = std::min(z_min, za[r]);
    }
    const double s = a_norm * z_norm + q_norm;
    double violation = z_norm > 0.0 ? -z_min / z_norm : 0.0;
    for (int i = 0; i < n && s > 0.0; ++i) {
      double w = qv[i];
      for (int r = 0; r < m; ++r) w += am[i][index[r]] * za[r];
      violation = std::max(violation, ((mask & (1u << i)) ? std::abs(w) : -w) / s);
    }
    if (violation < best) {
      best = violation;
      best_z = z;
      out.active = mask;
    }
  }
  out.violation = best;
  if (best <= settings.tol) {
    out.status = Status::solved;
    for (int i = 0; i < n; ++i) out.z(i) = std::max(best_z[i], 0.0);
  } else {
    out.active = 0;
  }
  return out;
}

}  // namespace pb::lcp
