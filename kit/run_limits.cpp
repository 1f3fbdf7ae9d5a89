#include "kit/run_limits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cases/text.hpp"

namespace pb {

const char* runaway(const System& sys, const double* u, const double* v) {
  const double bound = 1e6 * sys.length_scale();
  for (int i = 0; i < sys.n_bodies(); ++i)
    if (!(std::abs(u[static_cast<std::size_t>(i)]) <= bound)) return "|u| above 1e6 a_p/w_p^2";
  if (!(sys.energy(u, v) <= kDivergedEnergy * sys.energy_scale())) return "energy above 1e6 times its scale";
  return nullptr;
}

Status state_end(const System& sys, bool finite, const double* u, const double* v, double t, std::string& message) {
  const char* why = finite ? runaway(sys, u, v) : "non-finite state";
  if (!why) return Status::ok;
  message = std::string(why) + " at t = " + std::to_string(t);
  return finite ? Status::diverged : Status::nan;
}

Deadline::Deadline(const Settings& settings)
    : limit_(settings.time_limit),
      shown_(settings.point_time_limit > 0.0 ? settings.point_time_limit : settings.time_limit),
      stop_(settings.stop),
      start_(std::chrono::steady_clock::now()) {
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
  return "more than " + format_number(shown_) + " s of wall time";
}

}  // namespace pb
