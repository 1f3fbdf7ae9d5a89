#include "solvers/monitor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace pb {

namespace {

// System's start, or rest when it gives none (a System made by hand).
std::vector<double> start_or_rest(const std::vector<double>& start, const System& s) {
  return start.size() == s.bodies.size() ? start : std::vector<double>(s.bodies.size(), 0.0);
}

}  // namespace

StepMonitor::StepMonitor(const System& s)
    : s_(s),
      u_(start_or_rest(s.u_start, s)),
      rate_(static_cast<std::size_t>(s.n_contacts())),
      pushed_(static_cast<std::size_t>(s.n_contacts()), 0),
      energy_(s.energy(u_.data(), start_or_rest(s.v_start, s).data())),
      floor_(kRestitutionFloor * s.a_p / s.pulse.w),
      e_low_(std::numeric_limits<double>::quiet_NaN()),
      e_high_(std::numeric_limits<double>::quiet_NaN()) {
  const std::vector<double> v = start_or_rest(s.v_start, s);
  for (int j = 0; j < s.n_contacts(); ++j) {
    rate_[static_cast<std::size_t>(j)] = rate(j, v.data());
    fastest_ = std::max(fastest_, std::abs(rate_[static_cast<std::size_t>(j)]));
  }
}

double StepMonitor::rate(int j, const double* v) const { return s_.gap_rate(j, v); }

void StepMonitor::step(double h, double abar, const double* u, const double* v, const char* pushed) {
  double load = 0.0, damping = 0.0;
  for (std::size_t i = 0; i < u_.size(); ++i) {
    const double du = u[i] - u_[i];
    load += s_.bodies[i].m * du;
    damping += s_.bodies[i].c * du * du;
    u_[i] = u[i];
  }
  const double energy = s_.energy(u, v);
  balance_ += energy - energy_ + damping / h + abar * load;
  energy_ = energy;
  excess_ = std::max(excess_, balance_);

  const int nc = s_.n_contacts();
  int pushing = 0;
  for (int j = 0; j < nc; ++j) pushing += pushed[j] ? 1 : 0;
  for (int j = 0; j < nc; ++j) {
    const auto jj = static_cast<std::size_t>(j);
    const double before = rate_[jj];
    rate_[jj] = rate(j, v);
    fastest_ = std::max(fastest_, std::abs(rate_[jj]));
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
  r.gap_rate_max = fastest_;
}

Deadline::Deadline(const Settings& settings)
    : limit_(settings.time_limit), stop_(settings.stop), start_(std::chrono::steady_clock::now()) {}

bool Deadline::passed(long k) {
  if ((!(limit_ > 0.0) && !stop_) || k < next_) return false;
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
