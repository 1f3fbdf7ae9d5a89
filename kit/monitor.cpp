#include "kit/monitor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pb {

StepMonitor::StepMonitor(const System& s)
    : floor_(kRestitutionFloor * s.a_p / s.pulse.w),
      energy_scale_(s.energy_scale()),
      e_low_(std::numeric_limits<double>::quiet_NaN()),
      e_high_(std::numeric_limits<double>::quiet_NaN()) {
  const auto nb = static_cast<std::size_t>(s.n_bodies()), nc = static_cast<std::size_t>(s.n_contacts());
  std::vector<double> v(nb, 0.0);
  for (std::size_t i = 0; i < nb; ++i) {
    m_.push_back(s.bodies[i].m);
    c_.push_back(s.bodies[i].c);
    k_.push_back(s.bodies[i].k);
    u_.push_back(s.u_start.size() == nb ? s.u_start[i] : 0.0);  // rest when the System gives no start
    v[i] = s.v_start.size() == nb ? s.v_start[i] : 0.0;
  }
  energy_ = s.energy(u_.data(), v.data());
  for (int j = 0; j < s.n_contacts(); ++j) {
    left_.push_back(s.left(j));
    right_.push_back(s.right(j));
    rate_.push_back(s.gap_rate(j, v.data()));
    fastest_ = std::max(fastest_, std::abs(rate_.back()));
  }
  pushed_.assign(nc, 0);
}

void StepMonitor::finish(Result& r) const {
  r.energy_excess = excess_ / energy_scale_;
  r.isolated_impacts = isolated_;
  r.restitution_low = e_low_;
  r.restitution_high = e_high_;
  r.gap_rate_max = fastest_;
}

}  // namespace pb
