#include <array>
#include <cmath>
#include <stdexcept>

#include "solvers/event_driven/event_driven.hpp"
#include "solvers/external/external.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "solvers/settings_fields.hpp"
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
#ifdef POUNDBENCH_HAVE_SUNDIALS
#include "solvers/compliant/compliant.hpp"
#endif
#ifdef POUNDBENCH_HAVE_MUJOCO
#include "solvers/mujoco/mujoco_solver.hpp"
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

Result yielding_refused(std::string_view why) {
  Result r;
  r.status = Status::failed;
  r.message = "yielding: " + std::string(why);
  return r;
}

std::string check_step(const Settings& settings, int default_steps) {
  if (settings.steps < 0) return "steps: must be >= 1 (0: the default " + std::to_string(default_steps) + ")";
  if (!(settings.wh >= 0.0) || !std::isfinite(settings.wh)) return "wh: must be finite and > 0 (0: use steps)";
  if (settings.wh > 0.0 && settings.steps > 0) return "wh: give steps or wh, not both";
  return {};
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
    // Every solver is a deterministic sequence of floating-point operations: the stored
    // rows were reproduced bit for bit by the Release (-O3), RelWithDebInfo (-O2) and
    // sanitizer (-O0) builds of GCC 12. A baseline tolerance allows for another compiler or
    // libm, where round-off differs. The reference finds event times to an ulp and is exact
    // between them, so round-off stays round-off: 1e-9 (issue 7's figure), thousands of ulps.
    SolverInfo{"event-driven", "exact between events, Poisson impacts (the reference)", &event_driven::solve,
               &event_driven::describe, &check_all<&event_driven::check>, &event_driven::variant_list, 1e-9, true},
    // A time-stepper's round-off can flip an activation test that sits at its threshold and
    // move Pi1 by a step's worth; 1e-12 lets round-off through and catches any such flip.
    SolverInfo{"moreau-jean", "theta-method time-stepper, Newton impacts on predicted contacts (fixed step)",
               &moreau_jean::solve, &moreau_jean::describe, &check_all<&moreau_jean::check>, &moreau_jean::variant_list, 1e-12},
#ifdef POUNDBENCH_HAVE_ODE
    SolverInfo{"ode", "Open Dynamics Engine: its LCP contact solver with restitution (see --variant)", &ode::solve,
               &ode::describe, &check_all<&ode::check>, &ode::variant_list, 1e-12},
#endif
#ifdef POUNDBENCH_HAVE_BULLET
    // Debian's Bullet computes in single precision: the same margin at float round-off.
    SolverInfo{"bullet", "Bullet Physics (single precision): its constraint solvers with restitution (see --variant)",
               &bullet::solve, &bullet::describe, &check_all<&bullet::check>, &bullet::variant_list, 1e-6},
#endif
#ifdef POUNDBENCH_HAVE_SICONOS
    // Its LSODAR variant chooses its own steps, and round-off can move a step choice and Pi1
    // with it within its tolerances (1e-10 and below): as the reference.
    SolverInfo{"siconos", "Siconos: its MoreauJeanOSI, event-driven LSODAR and other nonsmooth integrators (see --variant)",
               &siconos::solve, &siconos::describe, &check_all<&siconos::check>, &siconos::variant_list, 1e-9},
#endif
#ifdef POUNDBENCH_HAVE_SUNDIALS
    // CVODE chooses its steps, and round-off can move a step choice and Pi1 with it within
    // its tolerance (1e-8 by default): 1e-7 lets that through.
    SolverInfo{"compliant", "compliant contact elements (see --variant), integrated by CVODE or Newmark",
               &compliant::solve, &compliant::describe, &check_all<&compliant::check>, &compliant::variant_list, 1e-7,
               false, &compliant::model_reference},
#endif
#ifdef POUNDBENCH_HAVE_MUJOCO
    // A fixed-step engine in double precision, as ODE: round-off only, 1e-12.
    SolverInfo{"mujoco", "MuJoCo: soft contacts calibrated to eps, Euler, implicit or RK4 (see --variant)",
               &mujoco::solve, &mujoco::describe, &check_all<&mujoco::check>, &mujoco::variant_list, 1e-12},
#endif
    // Another program, run once per point (docs/external.md): what it computes is its own; a
    // deterministic program gives its Pi1 again bit for bit, and 1e-9 lets another build of it
    // round differently, as the reference's.
    SolverInfo{"external", "another program, run per point: the case as JSON on its stdin, its answer on stdout (--command)",
               &external::solve, &external::describe, &check_all<&external::check>, &external::variant_list, 1e-9},
};

}  // namespace

std::span<const SolverInfo> solvers() { return kSolvers; }

const SolverInfo& reference_solver() {
  for (const SolverInfo& s : kSolvers)
    if (s.reference) return s;
  throw std::logic_error("the registry has no reference solver");
}

double no_contact_pi1(const System& system, const Settings& limits) {
  return event_driven::no_contact_pi1(system, limits);
}

std::vector<std::string_view> settings_used(const SolverInfo& solver, std::string_view variant) {
  Settings given;
  given.variant = variant;
  const std::string described = solver.describe(given);
  std::vector<std::string_view> used;
  for (const SettingField& field : kSettingFields) {
    Settings other = given;  // any other value: describe() does not check it
    if (field.number) other.*field.number += 1.0;
    if (field.integer) other.*field.integer += 1;
    if (field.count) other.*field.count += 1;
    if (field.text) other.*field.text += "?";
    if (solver.describe(other) != described) used.push_back(field.name);
  }
  return used;
}

const SolverInfo* find_solver(std::string_view solver_name) {
  for (const SolverInfo& s : kSolvers)
    if (s.name == solver_name) return &s;
  return nullptr;
}

std::string_view left_out_needs(std::string_view solver_name) {
  // The optional engines and their packages (CMakeLists.txt, scripts/setup.sh).
  constexpr std::array<std::array<std::string_view, 2>, 5> kOptional{{{"ode", "libode-dev"},
                                                                      {"bullet", "libbullet-dev"},
                                                                      {"siconos", "libsiconos-kernel-dev"},
                                                                      {"compliant", "libsundials-dev"},
                                                                      {"mujoco", "libmujoco-dev"}}};
  if (find_solver(solver_name)) return {};
  for (const auto& [solver, package] : kOptional)
    if (solver == solver_name) return package;
  return {};
}

}  // namespace pb
