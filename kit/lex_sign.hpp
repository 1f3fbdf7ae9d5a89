#pragma once
// The sign of a quantity from its Taylor coefficients at an instant, as both exact references
// decide their contact LCPs (solvers/event_driven, solvers/buildings_reference): the first
// coefficient that is not negligible (|c_k| > tol scale rate^k) decides.

namespace pb {

// True when the first coefficient that is not negligible is positive (or none is).
inline bool lex_nonnegative(const double* c, int n, double scale, double rate, double tol) {
  double z = tol * scale;
  for (int k = 0; k < n; ++k, z *= rate) {
    if (c[k] > z) return true;
    if (c[k] < -z) return false;
  }
  return true;
}

}  // namespace pb
