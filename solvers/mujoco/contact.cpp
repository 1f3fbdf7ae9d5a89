#include "solvers/mujoco/contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pb::mujoco {

double clamped_restitution(double zeta) {
  if (!(zeta > 0.0)) return 1.0;
  if (std::isinf(zeta)) return 0.0;
  if (zeta < 1.0) {
    const double s = std::sqrt(1.0 - zeta * zeta);
    const double phi = std::atan2(2.0 * zeta * s, 2.0 * zeta * zeta - 1.0);
    return std::exp(-zeta * phi / s);
  }
  if (zeta == 1.0) return std::exp(-2.0);
  const double s = std::sqrt(zeta * zeta - 1.0);
  return std::exp(-2.0 * zeta * std::log(zeta + s) / s);
}

double damping_ratio(double eps) {
  if (!(eps > 0.0)) return std::numeric_limits<double>::infinity();
  if (eps >= 1.0) return 0.0;
  // e(zeta) falls from 1 to 0: bracket in zeta, then bisect to 1e-14 of it.
  double lo = 0.0, hi = 1.0;
  while (clamped_restitution(hi) > eps) lo = hi, hi *= 2.0;
  while (hi - lo > 1e-14 * hi) {
    const double mid = 0.5 * (lo + hi);
    (clamped_restitution(mid) > eps ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double effective_impedance(double d) { return 3.0 * d / (1.0 + 2.0 * d); }

ContactParameters calibrated_contact(double eps, double contact_steps, double h) {
  const double d = kImpedance, de = effective_impedance(d);
  const double zeta = damping_ratio(eps);
  const double w_c = std::min(1.0 / (contact_steps * h), 1.0 / (2.0 * zeta * h));
  // Wanted: w_c^2 = de d k / dmax^2 and 2 zeta w_c = de b / dmax (dmax = d), the direct
  // form's k = -solref[0] / dmax^2, b = -solref[1] / dmax.
  const double k = std::isinf(zeta) ? 0.0 : w_c * w_c;
  const double b = std::isinf(zeta) ? 1.0 / h : 2.0 * zeta * w_c;
  ContactParameters p;
  p.solref = {-k * d / de, -b * d / de};
  // Written as -0 the zero damping of eps = 1 would still be a direct-form pair (no sign
  // mixes with -k), but +0 reads more plainly in a model file.
  if (p.solref[1] == 0.0) p.solref[1] = 0.0;
  if (p.solref[0] == 0.0) p.solref[0] = 0.0;
  p.solimp = {d, d, 0.001, 0.5, 2.0};
  return p;
}

ContactParameters default_contact() {
  ContactParameters p;
  p.solref = {0.02, 1.0};
  p.solimp = {0.9, 0.95, 0.001, 0.5, 2.0};
  return p;
}

}  // namespace pb::mujoco
