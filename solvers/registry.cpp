#include <array>
#include <cmath>

#include "solvers/event_driven/event_driven.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "solvers/solver.hpp"
#ifdef POUNDBENCH_HAVE_ODE
#include "solvers/ode/ode_solver.hpp"
#endif
#ifdef POUNDBENCH_HAVE_BULLET
#include "solvers/bullet/bullet_solver.hpp"
#endif
#ifdef POUNDBENCH_HAVE_SICONOS
#include "solvers/siconos/siconos_solver.hpp"
#endif

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

std::string check_step(const Settings& settings, int default_steps) {
  if (settings.steps < 0) return "steps: must be >= 1 (0: the default " + std::to_string(default_steps) + ")";
  if (!(settings.wh >= 0.0) || !std::isfinite(settings.wh)) return "wh: must be finite and > 0 (0: use steps)";
  if (settings.wh > 0.0 && settings.steps > 0) return "wh: give steps or wh, not both";
  return {};
}

std::string check_theta_method(const Settings& settings) {
  if (!(settings.theta >= 0.5 && settings.theta <= 1.0)) return "theta: must be in [0.5, 1]";
  if (!(settings.gamma >= 0.0 && settings.gamma <= 1.0)) return "gamma: must be in [0, 1]";
  return {};
}

std::string check_limits(const Settings& settings) {
  if (settings.step_cap < 0) return "step_cap: must be >= 0 (0: the solver's own cap)";
  if (!(settings.time_limit >= 0.0) || !std::isfinite(settings.time_limit))
    return "time_limit: must be finite and >= 0 (0: none)";
  return {};
}

namespace {

// The limits of a run mean the same to every solver, so they are checked here, where
// every solver is reached, and not left to each solver's own check (the reference's
// never looked at them: a negative --step-cap or a NaN --time-limit went through).
template <std::string (*OwnCheck)(const Settings&)>
std::string check_all(const Settings& settings) {
  if (std::string bad = check_limits(settings); !bad.empty()) return bad;
  return OwnCheck(settings);
}

const std::array kSolvers = {
    SolverInfo{"event-driven", "exact between events, Poisson impacts (the reference)", &event_driven::solve,
               &event_driven::describe, &check_all<&event_driven::check>},
    SolverInfo{"moreau-jean", "theta-method time-stepper, Newton impacts on predicted contacts (fixed step)",
               &moreau_jean::solve, &moreau_jean::describe, &check_all<&moreau_jean::check>},
#ifdef POUNDBENCH_HAVE_ODE
    SolverInfo{"ode", "Open Dynamics Engine: its LCP contact solver with restitution (see --variant)", &ode::solve,
               &ode::describe, &check_all<&ode::check>},
#endif
#ifdef POUNDBENCH_HAVE_BULLET
    SolverInfo{"bullet", "Bullet Physics (single precision): its constraint solvers with restitution (see --variant)",
               &bullet::solve, &bullet::describe, &check_all<&bullet::check>},
#endif
#ifdef POUNDBENCH_HAVE_SICONOS
    SolverInfo{"siconos", "Siconos: its MoreauJeanOSI (Lemke or enumeration) or event-driven LSODAR (see --variant)",
               &siconos::solve, &siconos::describe, &check_all<&siconos::check>},
#endif
};

}  // namespace

std::span<const SolverInfo> solvers() { return kSolvers; }

const SolverInfo* find_solver(std::string_view solver_name) {
  for (const SolverInfo& s : kSolvers)
    if (s.name == solver_name) return &s;
  return nullptr;
}

}  // namespace pb
