#include "kit/separation.hpp"

#include <algorithm>
#include <cmath>

namespace pb {

double cqc_rho(double xi_a, double xi_b, double r) {
  const double r2 = r * r;
  const double num = 8.0 * std::sqrt(xi_a * xi_b) * (xi_a + r * xi_b) * r * std::sqrt(r);
  const double den = (1.0 - r2) * (1.0 - r2) + 4.0 * xi_a * xi_b * r * (1.0 + r2) + 4.0 * (xi_a * xi_a + xi_b * xi_b) * r2;
  // Two undamped modes of one frequency: 0/0, whose limit along equal damping is 1.
  return den > 0.0 ? num / den : 1.0;
}

SeparationRules separation_rules(double u_a, double u_b, double rho) {
  SeparationRules out;
  out.abs = u_a + u_b;
  out.srss = std::hypot(u_a, u_b);
  // rho <= 1 keeps the sum >= (u_a - u_b)^2 >= 0; max() keeps round-off from a negative root.
  out.ddc = std::sqrt(std::max(0.0, u_a * u_a + u_b * u_b - 2.0 * rho * u_a * u_b));
  return out;
}

Separation separation(const System& s, const FreeMotion& given, const FreeMotion* reversed) {
  Separation out;
  for (int j = 0; j < s.n_contacts(); ++j) {
    out.required = std::max(out.required, given.closing[ix(j)]);
    out.reversed = std::max(out.reversed, reversed ? reversed->closing[ix(j)] : given.opening[ix(j)]);
    const int l = s.left(j), r = s.right(j);
    const double u_b = given.peak[ix(r)];
    const double u_a = l == kWall ? 0.0 : given.peak[ix(l)];
    const double rho = l == kWall ? 0.0 : cqc_rho(s.xi, s.xi, s.bodies[ix(r)].w / s.bodies[ix(l)].w);
    const SeparationRules rules = separation_rules(u_a, u_b, rho);
    out.rules.abs = std::max(out.rules.abs, rules.abs);
    out.rules.srss = std::max(out.rules.srss, rules.srss);
    out.rules.ddc = std::max(out.rules.ddc, rules.ddc);
  }
  return out;
}

std::vector<FloorSeparation> floor_separations(const BuildingModel& model, const buildings::BuildingsResult& free) {
  std::vector<FloorSeparation> out;
  out.reserve(free.contacts.size());
  for (const buildings::ContactResult& c : free.contacts) {
    FloorSeparation s;
    s.left = c.left;
    s.right = c.right;
    s.floor = c.floor;
    s.required = c.closing;
    s.reversed = c.opening;
    const auto l = static_cast<std::size_t>(c.left), r = static_cast<std::size_t>(c.right);
    const auto i = static_cast<std::size_t>(c.floor - 1);
    const auto peak = [&](std::size_t b) {
      return b < free.floor_peak.size() && i < free.floor_peak[b].size() ? free.floor_peak[b][i] : std::nan("");
    };
    s.peak_left = peak(l);
    s.peak_right = peak(r);
    const BuildingModes& a = model.modes[l];
    const BuildingModes& b = model.modes[r];
    s.period_ratio = a.w(0) / b.w(0);
    s.rho = cqc_rho(a.xi(0), b.xi(0), b.w(0) / a.w(0));
    s.rules = separation_rules(s.peak_left, s.peak_right, s.rho);
    out.push_back(s);
  }
  return out;
}

}  // namespace pb
