#include "solvers/monitor.hpp"

#include <algorithm>
#include <limits>

namespace pb {

StepMonitor::StepMonitor(const System& s)
    : s_(s),
      v_(s.v_start),
      rate_(static_cast<std::size_t>(s.n_contacts())),
      pushed_(static_cast<std::size_t>(s.n_contacts()), 0),
      energy_(s.energy(s.u_start.data(), s.v_start.data())),
      floor_(kRestitutionFloor * s.a_p / s.pulse.w),
      e_low_(std::numeric_limits<double>::quiet_NaN()),
      e_high_(std::numeric_limits<double>::quiet_NaN()) {
  for (int j = 0; j < s.n_contacts(); ++j) rate_[static_cast<std::size_t>(j)] = rate(j, v_.data());
}

double StepMonitor::rate(int j, const double* v) const {
  const int l = s_.left(j);
  return v[s_.right(j)] - (l == kWall ? 0.0 : v[l]);
}

void StepMonitor::step(double h, double abar, const double* u, const double* v, const char* pushed) {
  double momentum = 0.0, damping = 0.0;
  for (std::size_t i = 0; i < v_.size(); ++i) {
    const double mid = 0.5 * (v_[i] + v[i]);
    momentum += s_.bodies[i].m * mid;
    damping += s_.bodies[i].c * mid * mid;
    v_[i] = v[i];
  }
  const double energy = s_.energy(u, v);
  balance_ += energy - energy_ + h * (damping + abar * momentum);
  energy_ = energy;
  excess_ = std::max(excess_, balance_);

  const int nc = s_.n_contacts();
  int pushing = 0;
  for (int j = 0; j < nc; ++j) pushing += pushed[j] ? 1 : 0;
  for (int j = 0; j < nc; ++j) {
    const auto jj = static_cast<std::size_t>(j);
    const double before = rate_[jj];
    rate_[jj] = rate(j, v);
    if (pushing == 1 && pushed[j] && !pushed_[jj] && before < -floor_) {
      const double e = -rate_[jj] / before;
      ++isolated_;
      e_low_ = isolated_ == 1 ? e : std::min(e_low_, e);
      e_high_ = isolated_ == 1 ? e : std::max(e_high_, e);
    }
    pushed_[jj] = pushed[j];
  }
}

void StepMonitor::finish(Result& r) const {
  r.energy_excess = excess_ / s_.energy_scale();
  r.isolated_impacts = isolated_;
  r.restitution_low = e_low_;
  r.restitution_high = e_high_;
}

}  // namespace pb
