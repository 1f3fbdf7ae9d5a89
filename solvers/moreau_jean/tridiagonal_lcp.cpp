#include "solvers/moreau_jean/tridiagonal_lcp.hpp"

#include <algorithm>
#include <cstddef>

namespace pb::moreau_jean {

void TridiagonalLcp::reserve(int n) {
  const auto size = static_cast<std::size_t>(std::max(n, 0));
  in_.assign(size, 0);
  fresh_.assign(size, 0);
  c_.assign(size, 0.0);
  y_.assign(size, 0.0);
}

void TridiagonalLcp::solve_on_set(const double* d, const double* o, const double* q, double* z, int n) {
  int i = 0;
  while (i < n) {
    if (!in_[i]) {
      z[i++] = 0.0;
      continue;
    }
    const int a = i;
    bool fresh = false;
    for (; i < n && in_[i]; ++i) fresh = fresh || fresh_[i];
    const int b = i;
    if (!fresh) continue;  // the block is as it was: so is its solution
    // Forward elimination on the block [a, b): no pivoting, as the pivots of a positive
    // definite matrix are positive. z outside J is 0, so the block sees no neighbour.
    double inv = 1.0 / d[a];
    y_[a] = -q[a] * inv;
    for (int r = a + 1; r < b; ++r) {
      c_[r - 1] = o[r - 1] * inv;
      inv = 1.0 / (d[r] - o[r - 1] * c_[r - 1]);
      y_[r] = (-q[r] - o[r - 1] * y_[r - 1]) * inv;
    }
    z[b - 1] = y_[b - 1];
    for (int r = b - 2; r >= a; --r) z[r] = y_[r] - c_[r] * z[r + 1];
    for (int r = a; r < b; ++r) fresh_[r] = 0;
  }
}

int TridiagonalLcp::solve(const double* d, const double* o, const double* q, double* z, int n, const char* guess) {
  // The start: every contact that is not separating already (q_i <= 0: z_J = A_JJ^-1 (-q_J)
  // is >= 0 for it too, and contacts closed at rest, q_i = 0, join at once), and the guess.
  bool any = false;
  for (int i = 0; i < n; ++i) {
    in_[i] = fresh_[i] = static_cast<char>(q[i] <= 0.0 || (guess && guess[i]));
    any = any || in_[i];
  }
  if (!any) {
    std::fill(z, z + n, 0.0);
    return 0;
  }
  solve_on_set(d, o, q, z, n);
  int passes = 1;
  if (guess) {
    bool negative = false;
    for (int i = 0; i < n; ++i) negative = negative || z[i] < 0.0;
    if (negative) {  // the guess does not fit: start again without it
      for (int i = 0; i < n; ++i) in_[i] = fresh_[i] = static_cast<char>(q[i] <= 0.0);
      solve_on_set(d, o, q, z, n);
      ++passes;
    }
  }
  for (;;) {
    bool grown = false;
    for (int i = 0; i < n; ++i) {
      if (in_[i]) continue;
      double w = q[i];
      if (i > 0) w += o[i - 1] * z[i - 1];
      if (i + 1 < n) w += o[i] * z[i + 1];
      if (w < 0.0) {
        in_[i] = fresh_[i] = 1;
        grown = true;
      }
    }
    if (!grown) break;
    solve_on_set(d, o, q, z, n);
    ++passes;
  }
  // z >= 0 in exact arithmetic; a contact whose exact impulse is 0 may come out at -ulp.
  for (int i = 0; i < n; ++i) z[i] = std::max(z[i], 0.0);
  return passes;
}

}  // namespace pb::moreau_jean
