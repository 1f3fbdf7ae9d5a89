#include "kit/lcp/lemke.hpp"

#include <algorithm>
#include <cmath>

namespace pb::lcp {

void LemkeWorkspace::reserve(Eigen::Index n, Eigen::Index k) {
  binv.resize(n, n);
  x.resize(n, k);
  residual.resize(n, k);
  y.resize(n);
  d.resize(n);
  allow.resize(n);
  q_scale.resize(k);
  binv_row.resize(n);
  x_row.resize(k);
  basic.resize(n);
  cand.resize(n);
  row_norm.resize(n);
  saved_binv.resize(n, n);
  saved_x.resize(n, k);
  saved_basic.resize(n);
}

bool LemkeWorkspace::z_basic(Eigen::Index i) const {
  const Eigen::Index n = basic.size();
  for (Eigen::Index r = 0; r < n; ++r)
    if (basic(r) == n + i) return true;
  return false;
}

namespace {

// Whether every row of Q is lexicographically non-negative (its first entry that is not
// zero within the allowance is positive): then z = 0 solves LCP(A, q(s)) for small s > 0.
bool rows_lex_nonnegative(const Eigen::Ref<const Eigen::MatrixXd>& q, const Eigen::VectorXd& q_scale, double tol) {
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    for (Eigen::Index c = 0; c < q.cols(); ++c) {
      const double v = q(i, c);
      if (std::abs(v) <= tol * q_scale(c)) continue;
      if (v < 0.0) return false;
      break;
    }
  }
  return true;
}

// The lexicographic minimum ratio test over the m candidate rows ws.cand with divisors
// ws.d > 0: the row whose [x_i, binv_i] / d_i is lexicographically smallest, comparing one
// column at a time and keeping every row within rounding allowance of the column's
// minimum. If z0 is still among the candidates once the columns of Q are compared, it
// leaves: z0 = 0 is then reached with every row of B^-1 Q still lexicographically
// non-negative, which is all the solution needs.
Eigen::Index lex_min_ratio(LemkeWorkspace& ws, Eigen::Index m, Eigen::Index k, double tol, int z0) {
  const Eigen::Index n = ws.binv.rows();
  for (Eigen::Index c = 0; c < k + n && m > 1; ++c) {
    const double scale = c < k ? ws.q_scale(c) : 1.0;
    const auto value = [&](Eigen::Index p) {
      const Eigen::Index i = ws.cand(p);
      return (c < k ? ws.x(i, c) : ws.binv(i, c - k)) / ws.d(p);
    };
    for (Eigen::Index p = 0; p < m; ++p) ws.allow(p) = tol * ws.row_norm(p) * scale / ws.d(p);
    Eigen::Index best = 0;
    double v_best = value(0);
    for (Eigen::Index p = 1; p < m; ++p) {
      const double v = value(p);
      if (v < v_best) v_best = v, best = p;
    }
    const double a_best = ws.allow(best);
    Eigen::Index kept = 0;
    for (Eigen::Index p = 0; p < m; ++p) {
      if (value(p) > v_best + a_best + ws.allow(p)) continue;
      ws.cand(kept) = ws.cand(p);
      ws.d(kept) = ws.d(p);
      ws.row_norm(kept) = ws.row_norm(p);
      ++kept;
    }
    m = kept;
    if (c == k - 1)
      for (Eigen::Index p = 0; p < m; ++p)
        if (ws.basic(ws.cand(p)) == z0) return ws.cand(p);
  }
  // Rows that stay tied through every column differ only by rounding; the largest
  // pivot is the stable choice.
  Eigen::Index best = 0;
  for (Eigen::Index p = 1; p < m; ++p)
    if (ws.d(p) > ws.d(best)) best = p;
  return ws.cand(best);
}

// Exchanges the variable basic in row r for the one whose column is B^-1 a = ws.y.
void pivot(LemkeWorkspace& ws, Eigen::Index r) {
  const double p = ws.y(r);
  ws.binv_row = ws.binv.row(r) / p;
  ws.x_row = ws.x.row(r) / p;
  ws.y(r) = 0.0;
  ws.binv.noalias() -= ws.y * ws.binv_row;
  ws.x.noalias() -= ws.y * ws.x_row;
  ws.binv.row(r) = ws.binv_row;
  ws.x.row(r) = ws.x_row;
}

// x += B^-1 (Q - B x): the basis columns are e_j for w_j and -A_j for z_j (z0 has left).
void refine(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& q,
            LemkeWorkspace& ws) {
  const Eigen::Index n = q.rows();
  ws.residual = q;
  for (Eigen::Index r = 0; r < n; ++r) {
    const Eigen::Index v = ws.basic(r);
    if (v < n)
      ws.residual.row(v) -= ws.x.row(r);
    else
      ws.residual.noalias() += a.col(v - n) * ws.x.row(r);
  }
  ws.x.noalias() += ws.binv * ws.residual;
}

int complement(int v, Eigen::Index n) { return v < n ? v + static_cast<int>(n) : v - static_cast<int>(n); }

// ws.y = B^-1 times the column of variable v (e_j for w_j, -A_j for z_j); returns the
// column's largest magnitude.
double enter_column(const Eigen::Ref<const Eigen::MatrixXd>& a, LemkeWorkspace& ws, int v) {
  const Eigen::Index n = a.rows();
  if (v < n) {
    ws.y = ws.binv.col(v);
    return 1.0;
  }
  const Eigen::Index j = v - n;
  ws.y.noalias() = -ws.binv * a.col(j);
  return a.col(j).cwiseAbs().maxCoeff();
}

// The largest sign violation of the basic solution x.col(0), relative as a fit is
// measured: -z_j / ||z|| for a basic z_j, -w_j / s for a basic w_j, with
// s = ||A|| ||z|| + ||q||. Sets row to its row (-1 if nothing is negative).
double sign_violation(const LemkeWorkspace& ws, double a_norm, double q_norm, Eigen::Index& row) {
  const Eigen::Index n = ws.basic.size();
  double z_norm = 0.0;
  for (Eigen::Index r = 0; r < n; ++r)
    if (ws.basic(r) >= n) z_norm = std::max(z_norm, std::abs(ws.x(r, 0)));
  const double s = a_norm * z_norm + q_norm;
  double worst = 0.0;
  row = -1;
  for (Eigen::Index r = 0; r < n; ++r) {
    const double scale = ws.basic(r) >= n ? z_norm : s;
    const double v = scale > 0.0 ? -ws.x(r, 0) / scale : 0.0;
    if (v > worst) worst = v, row = r;
  }
  return worst;
}

// Lemke's path can end in a basis that is much worse conditioned than the problem needs:
// on a degenerate or ill-conditioned problem a variable that should be 0 sits in the
// basis, and its rounding (eps ||B^-1||) shows as a negative value. Exchanging the most
// negative basic variable for its complement, while that lowers the violation, reaches a
// basis that fits to rounding; it keeps the best basis seen.
void polish(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& q,
            LemkeWorkspace& ws, const LemkeSettings& settings) {
  constexpr double kTarget = 1e-15;  // a few eps: rounding-level already
  const Eigen::Index n = a.rows();
  const double a_norm = a.cwiseAbs().rowwise().sum().maxCoeff();
  Eigen::Index r = -1;
  double best = sign_violation(ws, a_norm, ws.q_scale(0), r);
  if (best <= kTarget) return;
  ws.saved_binv = ws.binv;
  ws.saved_x = ws.x;
  ws.saved_basic = ws.basic;
  bool at_best = true;
  for (Eigen::Index swap = 0; swap < n && r >= 0; ++swap) {
    const int entering = complement(ws.basic(r), n);
    const double col_norm = enter_column(a, ws, entering);
    if (!(std::abs(ws.y(r)) > settings.tol * ws.binv.row(r).lpNorm<1>() * col_norm)) break;
    pivot(ws, r);
    ws.basic(r) = entering;
    for (int s = 0; s < settings.refinement_steps; ++s) refine(a, q, ws);
    const double v = sign_violation(ws, a_norm, ws.q_scale(0), r);
    at_best = v < best;
    if (at_best) {
      best = v;
      ws.saved_binv = ws.binv;
      ws.saved_x = ws.x;
      ws.saved_basic = ws.basic;
      if (best <= kTarget) break;
    }
  }
  if (!at_best) {
    ws.binv = ws.saved_binv;
    ws.x = ws.saved_x;
    ws.basic = ws.saved_basic;
  }
}

}  // namespace

LemkeResult lemke_lex(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& q,
                      Eigen::Ref<Eigen::MatrixXd> z, LemkeWorkspace& ws, const LemkeSettings& settings) {
  LemkeResult out;
  const Eigen::Index n = q.rows(), k = q.cols();
  if (a.rows() != n || a.cols() != n || z.rows() != n || z.cols() != k || k < 1 || !a.allFinite() ||
      !q.allFinite())
    return out;
  z.setZero();
  ws.reserve(n, k);
  for (Eigen::Index i = 0; i < n; ++i) ws.basic(i) = static_cast<int>(i);
  out.status = Status::solved;
  if (n == 0) return out;
  const double tol = settings.tol;
  for (Eigen::Index c = 0; c < k; ++c) ws.q_scale(c) = q.col(c).cwiseAbs().maxCoeff();
  if (rows_lex_nonnegative(q, ws.q_scale, tol)) return out;

  const int z0 = static_cast<int>(2 * n);
  const int cap = settings.max_pivots > 0 ? settings.max_pivots : static_cast<int>(50 * n + 100);
  ws.binv.setIdentity();
  ws.x = q;

  // z0 enters along -d = -(1, ..., 1): every row bounds it from below, and the row that
  // leaves is the one of lexicographically smallest [Q_i, e_i], after which every row is
  // lexicographically positive.
  ws.y.setConstant(-1.0);
  for (Eigen::Index i = 0; i < n; ++i) {
    ws.cand(i) = static_cast<int>(i);
    ws.d(i) = 1.0;
    ws.row_norm(i) = 1.0;
  }
  Eigen::Index r = lex_min_ratio(ws, n, k, tol, z0);
  int entering = z0;
  for (;;) {
    const int leaving = ws.basic(r);
    pivot(ws, r);
    ws.basic(r) = entering;
    ++out.pivots;
    if (leaving == z0) break;
    if (out.pivots >= cap) {
      out.status = Status::iteration_cap;
      return out;
    }
    // The complement of the variable that left enters.
    entering = complement(leaving, n);
    const double col_norm = enter_column(a, ws, entering);
    Eigen::Index m = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!(ws.y(i) > 0.0)) continue;
      const double rn = ws.binv.row(i).lpNorm<1>();
      if (ws.y(i) <= tol * rn * col_norm) continue;
      ws.cand(m) = static_cast<int>(i);
      ws.d(m) = ws.y(i);
      ws.row_norm(m) = rn;
      ++m;
    }
    if (m == 0) {  // the entering variable can grow without bound: a secondary ray
      out.status = Status::no_solution;
      return out;
    }
    r = lex_min_ratio(ws, m, k, tol, z0);
  }

  for (int s = 0; s < settings.refinement_steps; ++s) refine(a, q, ws);
  if (k == 1 && settings.polish) polish(a, q, ws, settings);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index v = ws.basic(i);
    if (v >= n) z.row(v - n) = ws.x.row(i);
  }
  z.col(0) = z.col(0).cwiseMax(0.0);
  return out;
}

LemkeResult lemke(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::VectorXd>& q,
                  Eigen::Ref<Eigen::VectorXd> z, LemkeWorkspace& ws, const LemkeSettings& settings) {
  const Eigen::Map<const Eigen::MatrixXd> q_mat(q.data(), q.size(), 1);
  Eigen::Map<Eigen::MatrixXd> z_mat(z.data(), z.size(), 1);
  return lemke_lex(a, q_mat, z_mat, ws, settings);
}

}  // namespace pb::lcp
