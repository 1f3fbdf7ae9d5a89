#pragma once
// Lemke's complementary pivoting for LCP(A, q): find z >= 0, w = A z + q >= 0, z^T w = 0.
//
// Why Lemke: it is a finite, exact (up to rounding) method for any A for which it is
// known to work (P-matrices, positive semi-definite and more generally copositive-plus
// matrices: it then either solves the LCP or proves, by ending on a ray, that no solution
// exists), and its cost is a few n^2 operations per pivot with typically O(n) pivots.
// Enumeration (enumerate.hpp) is exact but costs 2^n; PGS (pgs.hpp) is cheap per sweep but
// only converges, and slowly when A is ill-conditioned.
//
// The method walks along an almost-complementary path of the augmented system
//   w = A z + q + d z0,  z, w, z0 >= 0,  z_i w_i = 0,
// starting where z = 0 and z0 = max(-q_i) makes w >= 0, and stops when z0 leaves the basis.
// Covering vector d = (1, ..., 1): every component of q is lifted at once by the first
// pivot, so the start needs no special basis, and ones are the usual choice for which
// the termination results above hold (any d > 0 would do; there is no better one a priori).
//
// Why lexicographic: contact problems are degenerate by nature (a contact that just closes
// has z_i = w_i = 0, and symmetric scenes tie exactly), and with ties in the minimum ratio
// test Lemke can cycle through bases forever. Breaking ties by comparing the rows of
// [B^-1 q | B^-1] divided by the pivot column -- the lexicographic minimum ratio test --
// picks a unique row (the rows of B^-1 are independent), keeps every row lexicographically
// positive, and so never revisits a basis: termination is guaranteed. It amounts to
// solving the LCP for q + (eps, eps^2, ..., eps^n) with eps -> 0+, exactly, without
// choosing eps. A smallest-index rule, which prevents cycling in the simplex method,
// does not here, where the entering variable is forced: Murty's 3 x 3 example cycles
// under it (tests/lcp_test.cpp).
//
// Lexicographic right-hand side: lemke_lex solves LCP(A, Q) for Q = [q, q', q'', ...]
// (n x k): the z returned solves LCP(A, q(s)) with q(s) = q + s q' + s^2 q'' + ... for every
// small enough s > 0, as z(s) = Z.col(0) + s Z.col(1) + s^2 Z.col(2) + .... It is the same
// lexicographic test with the columns of B^-1 Q placed before those of B^-1. An event-driven
// solver needs this when the load at a closed contact vanishes together with some of its
// derivatives: the first non-vanishing derivative decides whether the contact stays.
//
// B^-1 is kept explicitly (dense, row-major, updated in product form: about 5 n^2 flops
// per pivot) and the final basic solution is improved by iterative refinement against
// the original data, which removes the rounding the updates accumulate. On an
// ill-conditioned, degenerate problem the path may still end in a basis much worse
// conditioned than the problem needs; the plain solve then polishes (lemke.cpp).
// lemke_lex does not: exchanging variables on the evidence of the first column alone
// could break the lexicographic order that the higher columns define.

#include <Eigen/Core>

#include "kit/lcp/status.hpp"

namespace pb::lcp {

struct LemkeSettings {
  int max_pivots = 0;  // 0: 50 n + 100
  // Rounding allowance, relative: a basic value x_i = (B^-1 Q)_ic counts as equal to
  // another (in the ratio test) or to zero within tol ||row i of B^-1||_1 ||Q_c||, and a
  // pivot element y_i = (B^-1 a)_i is usable only above tol ||row i of B^-1||_1 ||a||.
  // These are the forward rounding bounds of the products with ~5e3 eps of margin for
  // the error the updates accumulate.
  double tol = 1e-12;
  int refinement_steps = 2;
  // Plain LCP only: after the path ends, exchange basic variables that are negative by
  // rounding for their complements while that improves the fit (see lemke.cpp). It
  // matters only on ill-conditioned, degenerate problems, and costs nothing otherwise.
  bool polish = true;
};

struct LemkeResult {
  Status status = Status::bad_input;
  int pivots = 0;
};

// Everything lemke needs besides its inputs: keep one per thread and pass it to every
// solve; once it has held a problem of size n x k, solving another of that size
// allocates nothing (a different size reallocates once).
struct LemkeWorkspace {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  RowMajor binv;             // B^-1 (its rows are what the ratio tests read)
  Eigen::MatrixXd x;         // B^-1 Q: the basic variables, one column per column of Q
  Eigen::MatrixXd residual;  // refinement: Q - B x
  Eigen::VectorXd y;         // B^-1 times the entering column
  Eigen::VectorXd d;         // ratio-test divisors of the candidate rows
  Eigen::VectorXd allow;     // ratio-test rounding allowances of the candidate rows
  Eigen::VectorXd q_scale;   // ||Q_c||_inf
  Eigen::RowVectorXd binv_row, x_row;  // the pivot row, copied before the update
  Eigen::VectorXi basic;     // variable basic in each row: w_j = j, z_j = n + j, z0 = 2n
  Eigen::VectorXi cand;      // candidate rows of the ratio test
  Eigen::VectorXd row_norm;  // ||row i of B^-1||_1 of the candidate rows
  RowMajor saved_binv;       // polish: the best basis so far
  Eigen::MatrixXd saved_x;
  Eigen::VectorXi saved_basic;

  void reserve(Eigen::Index n, Eigen::Index k);
  // After a solved call: whether z_i is basic, i.e. contact i is in the active set
  // (its z_i may be > 0 and w_i = 0; otherwise z_i = 0).
  bool z_basic(Eigen::Index i) const;
};

// Plain LCP(A, q). z must have the size of q; it receives the solution, or zeros if none.
LemkeResult lemke(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::VectorXd>& q,
                  Eigen::Ref<Eigen::VectorXd> z, LemkeWorkspace& ws, const LemkeSettings& settings = {});

// Lexicographic LCP(A, Q), Q = [q, q', ...] (n x k, k >= 1). z (n x k) receives the
// coefficients of z(s): z.col(0) solves LCP(A, q); z(s) solves LCP(A, q(s)) for small s > 0.
LemkeResult lemke_lex(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& q,
                      Eigen::Ref<Eigen::MatrixXd> z, LemkeWorkspace& ws, const LemkeSettings& settings = {});

}  // namespace pb::lcp
