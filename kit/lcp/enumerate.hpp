#pragma once
// Exact LCP solution by enumerating active sets: the ground truth of the tests.
//
//   find z >= 0 with w = A z + q >= 0 and z^T w = 0.
//
// Every solution has some active set alpha (z_i may be > 0 for i in alpha, z_i = 0
// elsewhere) on which w_alpha = 0, i.e. A_aa z_a = -q_a. Trying all 2^n sets, solving each
// principal subsystem by Gaussian elimination with complete pivoting and checking
// z_a >= 0, w_b >= 0, is exact up to rounding and needs no theory about A; its cost
// (2^n small solves) limits it to n <= kEnumerateMaxSize, which is all tests need.
//
// All 2^n sets are tried and the one that fits best is returned (the smallest relative
// violation of z_a >= 0, w_b >= 0, w_a = 0), if it fits within tol. Taking the first set
// within tol instead is not enough for a ground truth: with condition 1e10 a wrong active
// set can fit to 1e-9 while its z is O(1) away from the solution.
//
// Singular principal blocks are skipped. Nothing is lost by that: the particular solution
// of a consistent singular block, with its free variables set to zero, is the solution of
// a smaller active set, which the enumeration also visits; and for symmetric positive
// semi-definite A a vertex of the (convex) solution set has a nonsingular block.
//
// For a P-matrix the solution is unique; otherwise (PSD, degenerate q) several sets may
// fit to rounding, and the best of them (the first in bit-mask order on a tie) is returned.

#include <Eigen/Core>

#include "kit/lcp/status.hpp"

namespace pb::lcp {

inline constexpr int kEnumerateMaxSize = 12;

struct EnumerateSettings {
  // Acceptance of the best set, relative to the problem's size
  // s = ||A||_inf ||z||_inf + ||q||_inf: z_a >= -tol ||z||_inf, w_b >= -tol s,
  // |A_aa z_a + q_a| <= tol s. The violation of the true set is rounding (~1e-16).
  double tol = 1e-9;
  // A principal block whose smallest LU pivot is below this times its largest is taken as
  // singular; 1e-13 lies between rounding noise (~1e-16) and the conditioning (~1e-10)
  // of the worst problems the tests pose.
  double pivot_threshold = 1e-13;
};

struct EnumerateResult {
  Status status = Status::no_solution;
  Eigen::VectorXd z;    // the solution (negative rounding clamped to 0); zero if none
  unsigned active = 0;     // bit i set: i was in the accepted active set
  double violation = 0.0;  // of the best set, relative as in EnumerateSettings::tol
};

// status: solved, no_solution, or bad_input (n > kEnumerateMaxSize, sizes, non-finite).
EnumerateResult enumerate(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::VectorXd>& q,
                          const EnumerateSettings& settings = {});

}  // namespace pb::lcp
