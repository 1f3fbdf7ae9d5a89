#pragma once
// Projected Gauss-Seidel (PGS) for LCP(A, q): find z >= 0, w = A z + q >= 0, z^T w = 0.
//
// One sweep solves row i for z_i with the others fixed and projects onto z_i >= 0:
//   z_i <- max(0, z_i - omega (A z + q)_i / A_ii),
// using the z_j already updated in the sweep. For symmetric positive definite A this is
// coordinate descent on 1/2 z^T A z + q^T z over z >= 0 and converges for 0 < omega < 2
// (omega > 1: over-relaxation, PSOR). It is what time-stepping contact codes use: cheap
// sweeps, no allocation, warm starts from the previous step. It only converges, though,
// linearly and slowly when A is ill-conditioned (a long chain of contacts); lemke.hpp is
// the exact alternative.
//
// Stopping test: the natural residual of the diagonally scaled problem,
//   r = max_i |min(A_ii z_i, w_i)|,
// in the units of w (it is A_ii times the step a sweep would take at the current z), is
// zero exactly at a solution. A sweep whose largest step is below tol triggers one exact
// evaluation of r, and the solve stops when r <= tol; tol is absolute.
//
// pgs<N> takes fixed-size matrices (N known at compile time, no heap at all); the
// overload on Eigen::Ref takes any dense column-major matrix of run-time size.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

#include "kit/lcp/status.hpp"

namespace pb::lcp {

struct PgsSettings {
  double omega = 1.0;      // relaxation factor, in (0, 2)
  int max_sweeps = 1000;
  double tol = 1e-10;      // absolute, units of w: stop when max_i |min(A_ii z_i, w_i)| <= tol
};

struct PgsResult {
  Status status = Status::bad_input;  // solved, iteration_cap or bad_input (A_ii <= 0, sizes)
  int sweeps = 0;
  double residual = 0.0;  // max_i |min(A_ii z_i, w_i)| at the returned z (if evaluated)
};

namespace detail {

template <class MatA, class VecQ, class VecZ>
double pgs_residual(const MatA& a, const VecQ& q, const VecZ& z) {
  double r = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    const double w = a.row(i).dot(z) + q(i);
    r = std::max(r, std::abs(std::min(a(i, i) * z(i), w)));
  }
  return r;
}

template <class MatA, class VecQ, class VecZ>
PgsResult pgs_impl(const MatA& a, const VecQ& q, VecZ& z, const PgsSettings& s) {
  PgsResult out;
  const Eigen::Index n = q.size();
  if (a.rows() != n || a.cols() != n || z.size() != n || !(s.omega > 0.0 && s.omega < 2.0)) return out;
  for (Eigen::Index i = 0; i < n; ++i)
    if (!(a(i, i) > 0.0)) return out;
  for (Eigen::Index i = 0; i < n; ++i) z(i) = std::max(z(i), 0.0);  // a warm start may be infeasible
  out.status = Status::iteration_cap;
  while (out.sweeps < s.max_sweeps) {
    ++out.sweeps;
    double step = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double aii = a(i, i);
      const double w = a.row(i).dot(z) + q(i);
      const double zi = std::max(0.0, z(i) - s.omega * w / aii);
      step = std::max(step, aii * std::abs(zi - z(i)));
      z(i) = zi;
    }
    if (!std::isfinite(step)) {
      out.residual = step;
      return out;
    }
    if (step <= s.tol) {
      out.residual = pgs_residual(a, q, z);
      if (out.residual <= s.tol) {
        out.status = Status::solved;
        return out;
      }
    }
  }
  out.residual = pgs_residual(a, q, z);
  return out;
}

}  // namespace detail

// z: the warm start on entry (zeros for a cold start; negative entries are clamped), the
// last iterate on return.
template <int N>
PgsResult pgs(const Eigen::Matrix<double, N, N>& a, const Eigen::Matrix<double, N, 1>& q,
              Eigen::Matrix<double, N, 1>& z, const PgsSettings& settings = {}) {
  return detail::pgs_impl(a, q, z, settings);
}

PgsResult pgs(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::VectorXd>& q,
              Eigen::Ref<Eigen::VectorXd> z, const PgsSettings& settings = {});

}  // namespace pb::lcp
