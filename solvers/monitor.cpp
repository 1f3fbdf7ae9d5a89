#include "solvers/monitor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

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

Deadline::Deadline(const Settings& settings)
    : limit_(settings.time_limit), stop_(settings.stop), start_(std::chrono::steady_clock::now()) {
  if (!(limit_ > 0.0) && !stop_) next_ = std::numeric_limits<long>::max();
}

bool Deadline::look(long k) {
  if (stop_ && stop_->load(std::memory_order_relaxed)) return true;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (limit_ > 0.0 && elapsed > limit_) return true;
  // The next look after ~1 ms of steps at the mean cost so far (a look costs ~25 ns).
  const double per_step = elapsed / static_cast<double>(k);
  const double stride = per_step > 0.0 ? 1e-3 / per_step : 4096.0;
  next_ = k + std::clamp(static_cast<long>(stride), 1L, 4096L);
  return false;
}

std::string Deadline::reason() const {
  if (stop_ && stop_->load(std::memory_order_relaxed)) return "stopped (the sweep was interrupted)";
  std::ostringstream msg;
  msg << "more than " << limit_ << " s of wall time";
  return msg.str();
}

}  // namespace pb
