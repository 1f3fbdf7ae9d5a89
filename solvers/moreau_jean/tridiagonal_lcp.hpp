#pragma once
// The exact LCP of a run of consecutive contacts between bodies in a row:
//   find z >= 0 with w = A z + q >= 0 and z^T w = 0,
// where A = W^T M_hat^-1 W of the run is tridiagonal (contact j shares one body with j - 1
// and one with j + 1), symmetric positive definite, with off-diagonal entries
// -1 / m_hat_shared < 0: a Stieltjes matrix, a special M-matrix.
//
// Why not Lemke (lcp/lemke.hpp): it pivots on a dense inverse, O(n^2) per pivot and O(n)
// pivots, and knows nothing of the structure. For an M-matrix the solution is reached by
// growing an active set, each guess solved by a tridiagonal (Thomas) elimination in O(n)
// (Chandrasekaran's method for Z-matrices, 1970):
//
//   J = { i : q_i <= 0 };  loop { z_J = -A_JJ^-1 q_J, z = 0 off J;
//                                 add every i off J with w_i < 0 to J; stop if none }
//
// Why it is exact and finite: every principal submatrix A_JJ of an M-matrix is an
// M-matrix, so A_JJ^-1 >= 0 entrywise. The first z_J = A_JJ^-1 (-q_J) is >= 0. When the
// indices with w_i < 0 join J, the new z' satisfies A_J'J' (z' - z)_J' = -w_J' >= 0
// (w_J = 0, w < 0 on the newcomers), so z' >= z >= 0: z only grows and stays >= 0.
// J grows at every pass, so there are at most n passes; the last has z >= 0 on J with
// w_J = 0, z = 0 and w >= 0 off J, which is the solution (unique: A is a P-matrix).
// Ties need no rule: any start whose z_J is >= 0 keeps the argument, and an index joins
// later only when w_i < 0.
//
// Cost: O(n) per pass, and a pass re-solves only the blocks of J that grew. The start takes
// the contacts with q_i = 0 (closed and at rest, as in a Newton's cradle hit at one end) at
// once, so an impulse that has to travel along the run does not cost one pass per contact.
// A warm start from the contacts that pushed in the step before (still exact, by the
// argument above, whenever its z_J is >= 0) makes persistent contact one pass; a start
// that gives some z_i < 0 falls back to the cold start.
//
// Holds its scratch from reserve() on: solving a run no longer than that allocates nothing.

#include <vector>

namespace pb::moreau_jean {

class TridiagonalLcp {
 public:
  void reserve(int n);

  // A: d[0..n) on the diagonal, o[0..n-1) beside it (A(i, i+1) = A(i+1, i) = o[i] <= 0).
  // guess (may be null): contacts expected to push, a warm start. z receives the solution.
  // Returns the number of tridiagonal solves (passes) it took.
  int solve(const double* d, const double* o, const double* q, double* z, int n, const char* guess);

 private:
  // z_J = -A_JJ^-1 q_J on every block of consecutive members of J, z = 0 elsewhere.
  void solve_on_set(const double* d, const double* o, const double* q, double* z, int n);

  std::vector<char> in_;    // membership of J
  std::vector<char> fresh_;  // joined J since its block was last solved
  std::vector<double> c_;   // Thomas: the eliminated super-diagonal
  std::vector<double> y_;   // Thomas: the forward-substituted right-hand side
};

}  // namespace pb::moreau_jean
