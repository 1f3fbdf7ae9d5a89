#pragma once
// Poisson's impact law for frictionless, centric contacts of bodies in a row, through the
// compression and expansion LCPs of Pfeiffer & Glocker (the paper's eqs 2 and 3, with the
// expansion complementarity on the extra impulse Lambda_P = Lambda_E - eps Lambda_C, as
// cases/README.md prescribes):
//
//   compression: gd_C = G Lambda_C + gd_A,               0 <= gd_C  perp  Lambda_C >= 0
//   expansion:   gd_E = G Lambda_P + eps G Lambda_C + gd_C, 0 <= gd_E perp Lambda_P >= 0
//
// with G = W^T M^-1 W over the contacts of the impact and gd the normal relative
// velocities. For one contact this is gd_E = -eps gd_A, which is also Newton's law.
//
// G couples only contacts that share a body, so an impact set splits into runs of
// consecutive contacts that are independent problems. A run of one contact has a closed
// form, of two the exact four-set enumeration (lcp::solve2). Longer runs use that G is
// a tridiagonal M-matrix: Chandrasekaran's active-set method, O(n) per step, with Lemke's
// method (lcp::lemke, O(n^2) per pivot) as the fallback. G is positive definite, so the
// solution is unique.

#include <span>
#include <vector>

#include <Eigen/Core>

#include "cases/system.hpp"
#include "kit/lcp/lemke.hpp"

namespace pb::event_driven {

struct ImpactOutcome {
  std::vector<double> impulse;   // total impulse Lambda_C + Lambda_E per contact of the set
  std::vector<double> gap_rate;  // gd_E per contact of the set
};

// What the impacts of one run of the solver reuse, so that an impact allocates nothing
// once the largest run has been seen.
struct ImpactWork {
  bool lemke_only = false;  // runs of three or more by Lemke's method alone (for checks)
  lcp::LemkeWorkspace lemke;
  Eigen::VectorXd main, off;        // G of the run: diagonal, off-diagonal
  Eigen::MatrixXd g;                // G as a dense matrix, for Lemke's method
  Eigen::VectorXd gd, rhs, lc, lp;  // approach rates, expansion data, impulses
  Eigen::VectorXd pivot;            // Thomas algorithm: the eliminated diagonal
  std::vector<char> in;             // Chandrasekaran's method: the contacts with w = 0
  Eigen::VectorXd q;                // its right-hand side, rounding set to zero
};

// Applies the impact on one run of contacts (ascending System contact indices, each
// sharing a body with the next) to the body velocities v (left to right), in place; writes
// the total impulse per contact into `impulse` (the run's size). Throws std::runtime_error
// if Lemke's method fails on a long run (it should not: G is positive definite).
void poisson_run(const System& s, std::span<const int> run, std::span<double> v, double eps, ImpactWork& work,
                 std::span<double> impulse);

// Applies the impact on the contacts `set` (ascending System contact indices) to v, run by
// run. For tests and one-off use: it allocates its own workspace.
ImpactOutcome poisson_impact(const System& s, std::span<const int> set, std::span<double> v, double eps);

// Normal relative velocity of contact j: d/dt (delta + u_right - u_left).
double gap_rate(const System& s, int j, std::span<const double> v);

// Calls f(begin, end) for each maximal run [begin, end) of contacts in `set` (ascending)
// whose neighbours share a body.
template <class F>
void for_each_run(const System& s, std::span<const int> set, F&& f) {
  for (std::size_t begin = 0; begin < set.size();) {
    std::size_t end = begin + 1;
    while (end < set.size() && s.right(set[end - 1]) == s.left(set[end])) ++end;
    f(begin, end);
    begin = end;
  }
}

}  // namespace pb::event_driven
