#pragma once
// Exact solutions of the small LCPs that pounding scenes produce:
//   find z >= 0 with w = A z + q >= 0 and z^T w = 0.
// One contact has a closed form; two contacts are solved by enumerating the four active
// sets, which is exact and branch-light. A is assumed to be a P-matrix (true of
// W^T M^-1 W for bodies in a row), so exactly one active set fits.

#include <Eigen/Core>

namespace pb::lcp {

inline double solve1(double a, double q) { return q >= 0.0 ? 0.0 : -q / a; }

// Returns z; for a P-matrix one of the four candidates always satisfies the conditions.
inline Eigen::Vector2d solve2(const Eigen::Matrix2d& a, const Eigen::Vector2d& q) {
  if (q(0) >= 0.0 && q(1) >= 0.0) return Eigen::Vector2d::Zero();
  // Only z0 > 0.
  {
    const double z0 = -q(0) / a(0, 0);
    if (z0 >= 0.0 && q(1) + a(1, 0) * z0 >= 0.0) return {z0, 0.0};
  }
  // Only z1 > 0.
  {
    const double z1 = -q(1) / a(1, 1);
    if (z1 >= 0.0 && q(0) + a(0, 1) * z1 >= 0.0) return {0.0, z1};
  }
  // Both: w = 0.
  const double det = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0);
  return {(-q(0) * a(1, 1) + a(0, 1) * q(1)) / det, (-a(0, 0) * q(1) + a(1, 0) * q(0)) / det};
}

}  // namespace pb::lcp
