#include "kit/solver.hpp"

#include <cmath>
#include <numbers>

#include "cases/text.hpp"

namespace pb {

std::string_view name(Status s) {
  switch (s) {
    case Status::ok: return "ok";
    case Status::diverged: return "diverged";
    case Status::nan: return "nan";
    case Status::step_cap: return "step_cap";
    case Status::time_limit: return "time-limit";
    case Status::failed: return "failed";
    case Status::penetration: return "penetration";
    case Status::energy: return "energy";
  }
  return "?";
}

std::optional<Status> parse_status(std::string_view text) {
  for (Status s : {Status::ok, Status::diverged, Status::nan, Status::step_cap, Status::time_limit, Status::failed,
                   Status::penetration, Status::energy})
    if (name(s) == text) return s;
  return std::nullopt;
}

Result failed(std::string message) {
  Result r;
  r.status = Status::failed;
  r.message = std::move(message);
  return r;
}

Result yielding_refused(std::string_view why) { return failed("yielding: " + std::string(why)); }

std::string check_step(const Settings& settings, int default_steps) {
  if (settings.steps < 0) return "steps: must be >= 1 (0: the default " + std::to_string(default_steps) + ")";
  if (!(settings.wh >= 0.0) || !std::isfinite(settings.wh)) return "wh: must be finite and > 0 (0: use steps)";
  if (settings.wh > 0.0 && settings.steps > 0) return "wh: give steps or wh, not both";
  if (!(settings.h_s >= 0.0) || !std::isfinite(settings.h_s)) return "h_s: must be finite and > 0 (s; 0: use steps)";
  if (settings.h_s > 0.0 && (settings.steps > 0 || settings.wh > 0.0))
    return "h_s: give the step one way (steps, wh or h_s)";
  if (settings.steps_per_sample < 0) return "steps_per_sample: must be >= 1 (0: the step T_min / N alone)";
  return {};
}

std::string step_rule_problem(const System& system, const Settings& settings) {
  if (settings.steps_per_sample <= 0 || system.pulse.record) return {};
  return "steps_per_sample: the step rule `record` needs a record's samples, and this case's load is a pulse "
         "(its step is T_min / N: leave it out)";
}

std::string step_problem(const System& system, double h) {
  const double t_p = 2.0 * std::numbers::pi / system.pulse.w;
  // 1e-12: a step of exactly T_p (w_max h = 2 pi on a case whose pulse is its fastest) may
  // round a few ulps above it.
  if (h <= t_p * (1.0 + 1e-12)) return {};
  return std::string(kStepBoundMessage) + format_number(h) + " is longer than the pulse period T_p = " + format_number(t_p) +
         " (w_p h = " + format_number(h * system.pulse.w) + " > 2 pi): a run takes at least one step per pulse; "
         "give a smaller --wh, or --steps";
}

std::string check_theta_method(const Settings& settings) {
  if (!(settings.theta >= 0.5 && settings.theta <= 1.0)) return "theta: must be in [0.5, 1]";
  return check_gamma(settings);
}

std::string check_gamma(const Settings& settings) {
  if (!(settings.gamma >= 0.0 && settings.gamma <= 1.0)) return "gamma: must be in [0, 1]";
  return {};
}

std::string check_limits(const Settings& settings) {
  if (settings.step_cap < 0) return "step_cap: must be >= 0 (0: the solver's own cap)";
  if (!(settings.time_limit >= 0.0) || !std::isfinite(settings.time_limit))
    return "time_limit: must be finite and >= 0 (0: none)";
  return {};
}

}  // namespace pb
