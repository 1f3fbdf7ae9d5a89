#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "cases/record.hpp"
#include "cases/record_scale.hpp"
#include "cases/system.hpp"
#include "cases/text.hpp"
#include "solvers/buildings_reference/reference.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/external/external.hpp"
#include "solvers/moreau_jean/buildings.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "kit/settings_fields.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#ifdef POUNDBENCH_HAVE_ODE
#include "solvers/ode/buildings.hpp"
#include "solvers/ode/ode_solver.hpp"
#endif
#ifdef POUNDBENCH_HAVE_BULLET
#include "solvers/bullet/buildings.hpp"
#include "solvers/bullet/bullet_solver.hpp"
#endif
#ifdef POUNDBENCH_HAVE_SICONOS
#include "solvers/siconos/buildings.hpp"
#include "solvers/siconos/siconos_solver.hpp"
#endif
#ifdef POUNDBENCH_HAVE_SUNDIALS
#include "solvers/compliant/buildings.hpp"
#include "solvers/compliant/compliant.hpp"
#endif
#ifdef POUNDBENCH_HAVE_MUJOCO
#include "solvers/mujoco/buildings.hpp"
#include "solvers/mujoco/mujoco_solver.hpp"
#endif
#ifdef POUNDBENCH_HAVE_DART
#include "solvers/dart/buildings.hpp"
#include "solvers/dart/dart_solver.hpp"
#endif
#ifdef POUNDBENCH_HAVE_SIMBODY
#include "solvers/simbody/buildings.hpp"
#include "solvers/simbody/simbody_solver.hpp"
#endif

namespace pb {

namespace {

// What every solver's check does besides its own, defined below the table: the limits of a
// run (they mean the same to every solver: the reference's own check never looked at them,
// and a negative --step-cap or a NaN --time-limit went through) and unused_setting's rule.
template <std::string (*OwnCheck)(const Settings&)>
std::string check_all(const Settings& settings);

// The order of Pi1 in the step that a fixed-step run's error estimate assumes
// (SolverInfo::step_order). Pi1 is the largest |u0| over the step ends: where that maximum is
// smooth a second-order scheme reads it to O(h^2), but where it sits at an impact (u0' jumps:
// a kink of |u0|) the step ends sample it to O(h) whatever the scheme, and every scheme here
// is first order through its impacts (Moreau-Jean at theta = 1/2 included). So p = 1, the
// conservative choice: a p of 2 would divide the estimate by 3. Measured on the 200 random wall
// and pair cases of scripts/estimate_reliability.py against the reference, the order of Pi1's
// error from N to 2N (N = 32 .. 256): Moreau-Jean 1.4 to 1.6 in the median case, its quartiles
// 0.5 to 2.5 (erratic: impacts move between step ends); ODE 1.0 to 1.06, quartiles 0.4 to 1.5.
constexpr double kFixedStepOrder = 1.0;

// What the buildings scene's exact reference reads: its tolerances' scale and the limits.
constexpr std::string_view kExactBuildingsSettings[] = {"tol_scale", "step_cap", "time_limit"};

// What Moreau-Jean's buildings solve reads (solvers/moreau_jean/buildings.hpp); its variants,
// the load rules, apply to the scene as they are.
constexpr std::string_view kMoreauJeanBuildingsSettings[] = {"steps", "wh", "h_s", "steps_per_sample", "theta", "gamma",
                                                             "step_cap", "time_limit"};

const std::array kSolvers = {
    // Every solver is a deterministic sequence of floating-point operations: the stored
    // rows were reproduced bit for bit by the Release (-O3), RelWithDebInfo (-O2) and
    // sanitizer (-O0) builds of GCC 12. A baseline tolerance allows for another compiler or
    // libm, where round-off differs. The reference finds event times to an ulp and is exact
    // between them, so round-off stays round-off: 1e-9 (issue 7's figure), thousands of ulps.
    SolverInfo{.name = "event-driven",
               .summary = "exact between events, Poisson impacts (the reference)",
               .solve = &event_driven::solve,
               .describe = &event_driven::describe,
               .check = &check_all<&event_driven::check>,
               .variants = &event_driven::variant_list,
               .baseline_tolerance = 1e-9,
               .reference = true,
               .solve_buildings = &buildings::solve,
               .buildings_settings = kExactBuildingsSettings},
    // A time-stepper's round-off can flip an activation test that sits at its threshold and
    // move Pi1 by a step's worth; 1e-12 lets round-off through and catches any such flip.
    SolverInfo{.name = "moreau-jean",
               .summary = "theta-method time-stepper, Newton impacts on predicted contacts (fixed step)",
               .solve = &moreau_jean::solve,
               .describe = &moreau_jean::describe,
               .check = &check_all<&moreau_jean::check>,
               .variants = &moreau_jean::variant_list,
               .baseline_tolerance = 1e-12,
               .step_order = kFixedStepOrder,
               .solve_buildings = &moreau_jean::solve_buildings,
               .buildings_settings = kMoreauJeanBuildingsSettings},
#ifdef POUNDBENCH_HAVE_ODE
    // On the buildings scene: a body per floor, the storeys' forces applied (solvers/ode/buildings.hpp).
    SolverInfo{.name = "ode",
               .summary = "Open Dynamics Engine: its LCP contact solver with restitution (see --variant)",
               .solve = &ode::solve,
               .describe = &ode::describe,
               .check = &check_all<&ode::check>,
               .variants = &ode::variant_list,
               .baseline_tolerance = 1e-12,
               .step_order = kFixedStepOrder,
               .solve_buildings = &ode::solve_buildings,
               .buildings_settings = ode::kBuildingsSettings},
#endif
#ifdef POUNDBENCH_HAVE_BULLET
    // Debian's Bullet computes in single precision: the same margin at float round-off.
    // On the buildings scene: a body per floor, the storeys' forces applied (solvers/bullet/buildings.hpp).
    SolverInfo{.name = "bullet",
               .summary = "Bullet Physics (single precision): its constraint solvers with restitution (see --variant)",
               .solve = &bullet::solve,
               .describe = &bullet::describe,
               .check = &check_all<&bullet::check>,
               .variants = &bullet::variant_list,
               .baseline_tolerance = 1e-6,
               .step_order = kFixedStepOrder,
               .solve_buildings = &bullet::solve_buildings,
               .buildings_settings = bullet::kBuildingsSettings},
#endif
#ifdef POUNDBENCH_HAVE_SICONOS
    // Its LSODAR variant chooses its own steps, and round-off can move a step choice and Pi1
    // with it within its tolerances (1e-10 and below): as the reference.
    // On the buildings scene: MoreauJeanOSI with the buildings' M, C, K (solvers/siconos/buildings.hpp).
    SolverInfo{.name = "siconos",
               .summary = "Siconos: its MoreauJeanOSI, event-driven LSODAR and other nonsmooth integrators (see --variant)",
               .solve = &siconos::solve,
               .describe = &siconos::describe,
               .check = &check_all<&siconos::check>,
               .variants = &siconos::variant_list,
               .baseline_tolerance = 1e-9,
               .step_order = kFixedStepOrder,
               .solve_buildings = &siconos::solve_buildings,
               .buildings_settings = siconos::kBuildingsSettings},
#endif
#ifdef POUNDBENCH_HAVE_SUNDIALS
    // CVODE chooses its steps, and round-off can move a step choice and Pi1 with it within
    // its tolerance (1e-8 by default): 1e-7 lets that through.
    // On the buildings scene: an element at every floor pair (solvers/compliant/buildings.hpp).
    SolverInfo{.name = "compliant",
               .summary = "compliant contact elements (see --variant), integrated by CVODE or Newmark",
               .solve = &compliant::solve,
               .describe = &compliant::describe,
               .check = &check_all<&compliant::check>,
               .variants = &compliant::variant_list,
               .baseline_tolerance = 1e-7,
               .model_reference = &compliant::model_reference,
               .step_order = kFixedStepOrder,
               .hertz_contact = &compliant::hertz_contact,
               .solve_buildings = &compliant::solve_buildings,
               .buildings_settings = compliant::kBuildingsSettings},
#endif
#ifdef POUNDBENCH_HAVE_MUJOCO
    // A fixed-step engine in double precision, as ODE: round-off only, 1e-12.
    // On the buildings scene: a body per floor on a slide joint, tendons for the storeys
    // (solvers/mujoco/buildings.hpp).
    SolverInfo{.name = "mujoco",
               .summary = "MuJoCo: soft contacts calibrated to eps, Euler, implicit or RK4 (see --variant)",
               .solve = &mujoco::solve,
               .describe = &mujoco::describe,
               .check = &check_all<&mujoco::check>,
               .variants = &mujoco::variant_list,
               .baseline_tolerance = 1e-12,
               .step_order = kFixedStepOrder,
               .solve_buildings = &mujoco::solve_buildings,
               .buildings_settings = mujoco::kBuildingsSettings},
#endif
#ifdef POUNDBENCH_HAVE_DART
    // A fixed-step engine in double precision, as ODE: round-off only, 1e-12.
    // On the buildings scene: a body per floor (solvers/dart/buildings.hpp).
    SolverInfo{"dart", "DART: its constraint solver with a gap constraint of its own, or boxes via FCL (see --variant)",
               &dart::solve, &dart::describe, &check_all<&dart::check>, &dart::variant_list, 1e-12, false, nullptr, false, kFixedStepOrder,
               nullptr, {}, &dart::solve_buildings, dart::kBuildingsSettings},
#endif
#ifdef POUNDBENCH_HAVE_SIMBODY
    // Its time-stepper, in double precision, is deterministic: round-off only, 1e-12. Its
    // hunt-crossley variant's Runge-Kutta-Merson chooses its steps, and round-off can move a
    // choice and Pi1 with it within its accuracy (1e-8 by default): 1e-7, as CVODE's.
    // On the buildings scene: a slider per floor, its time-stepper (solvers/simbody/buildings.hpp).
    SolverInfo{"simbody", "Simbody: its semi-explicit Euler time-stepper with Poisson impacts, or Hunt-Crossley elements (see --variant)",
               &simbody::solve, &simbody::describe, &check_all<&simbody::check>, &simbody::variant_list, 1e-7, false, nullptr, false, kFixedStepOrder,
               &simbody::hertz_contact, {}, &simbody::solve_buildings, simbody::kBuildingsSettings},
#endif
    // Another program, run once per point (docs/external.md): what it computes is its own; a
    // deterministic program gives its Pi1 again bit for bit, and 1e-9 lets another build of it
    // round differently, as the reference's.
    // Solved once per point (one_pass): a second, monitored pass would run the user's program twice.
    // On the buildings scene: the scene's documents (programs/buildings_protocol.hpp), per point or persistent.
    SolverInfo{.name = "external",
               .summary = "another program, run per point: the case as JSON on its stdin, its answer on stdout (--command)",
               .solve = &external::solve,
               .describe = &external::describe,
               .check = &check_all<&external::check>,
               .variants = &external::variant_list,
               .baseline_tolerance = 1e-9,
               .one_pass = true,
               .solve_buildings = &external::solve_buildings,
               .buildings_settings = external::kBuildingsSettings},
};

// The row whose check this is finds its describe() in the table, so that a row added as
// `&check_all<&X::check>` has every rule without naming its describe() twice.
template <std::string (*OwnCheck)(const Settings&)>
std::string check_all(const Settings& settings) {
  if (std::string bad = check_limits(settings); !bad.empty()) return bad;
  if (std::string bad = OwnCheck(settings); !bad.empty()) return bad;
  for (const SolverInfo& solver : kSolvers)
    if (solver.check == &check_all<OwnCheck>) return unused_setting(solver, settings);
  return {};
}

// `settings` with one field set to its default, or (`moved`) to another value.
Settings with_field(Settings settings, const SettingField& field, bool moved) {
  const Settings d;
  if (field.number) settings.*field.number = d.*field.number + (moved ? 1.0 : 0.0);
  if (field.integer) settings.*field.integer = d.*field.integer + (moved ? 1 : 0);
  if (field.count) settings.*field.count = d.*field.count + (moved ? 1 : 0);
  if (field.text) settings.*field.text = d.*field.text + (moved ? "?" : "");
  return settings;
}

bool is_default(const Settings& settings, const SettingField& field) {
  static const Settings d;
  if (field.text) return settings.*field.text == d.*field.text;
  return field.get(settings) == field.get(d);  // NaN is never the default
}

}  // namespace

std::string unused_setting(const SolverInfo& solver, const Settings& settings, const GivenSetting& given) {
  for (const SettingField& field : kSettingFields) {
    if (field.name == "step_cap" || field.name == "time_limit") continue;  // every solver's
    // With `given` (after the solver's check), a value other than the default was checked by
    // that check (check_all, these settings): a field given at its default is what is left.
    // Checked twice, it was 40 k instructions of a poundbench.run call's 255 k (describe()
    // four times; callgrind, Moreau-Jean with steps given).
    if (given ? !is_default(settings, field) || !given(field.name) : is_default(settings, field)) continue;
    // Used when its value changes what describe() says the run is, the other fields as given.
    if (solver.describe(with_field(settings, field, false)) != solver.describe(with_field(settings, field, true)))
      continue;
    const std::string variant = settings.variant.empty() ? "its default variant" : "variant " + settings.variant;
    return std::string(field.name) + ": not used by " + std::string(solver.name) + " (" + clip(variant) +
           ", with these settings); leave it out (`poundbench solvers` lists what each variant uses)";
  }
  return {};
}

std::span<const SolverInfo> solvers() { return kSolvers; }

bool is_own_setting(std::string_view name) {
  for (const SolverInfo& s : solvers())
    if (own_setting_index(s.own_settings, name)) return true;
  return false;
}

const SolverInfo& reference_solver() {
  for (const SolverInfo& s : kSolvers)
    if (s.reference) return s;
  throw std::logic_error("the registry has no reference solver");
}

double no_contact_pi1(const System& system, const Settings& limits) {
  return event_driven::no_contact_pi1(system, limits);
}

FreeMotion free_motion(const System& system, const Settings& limits) { return event_driven::free_motion(system, limits); }

buildings::BuildingsResult buildings_free_motion(const BuildingScene& scene, const Settings& limits) {
  return buildings::free_motion(scene, limits);
}

// Declared by cases/record_scale.hpp, which sits below the reference: the oscillator as the
// wall scene's body 0 (its contact unused: free_motion removes it), in the record's own units.
double pseudo_acceleration(const Record& record, double period, double xi) {
  Case c;
  c.scene = Scene::wall;
  c.pulse = PulseShape::record;
  c.record = record.source;
  c.samples = std::shared_ptr<const Record>(std::shared_ptr<const Record>{}, &record);  // not owned: the caller's
  c.record_scale = record.scale;
  c.a_p = record.peak;
  c.w_p = 2.0 * std::numbers::pi / period;
  c.pi2 = 1.0;
  c.xi = xi;
  if (auto bad = validate(c)) throw std::invalid_argument("sa_period: " + *bad);
  const FreeMotion free = free_motion(make_system(c), Settings{});
  if (free.status != Status::ok) throw std::runtime_error("sa: the oscillator's solve: " + free.message);
  return c.w_p * c.w_p * free.peak[0];
}

std::vector<std::string_view> settings_used(const SolverInfo& solver, std::string_view variant) {
  Settings given;
  given.variant = variant;
  const std::string described = solver.describe(given);
  std::vector<std::string_view> used;
  for (const SettingField& field : kSettingFields)  // any other value: describe() does not check it
    if (solver.describe(with_field(given, field, true)) != described) used.push_back(field.name);
  return used;
}

std::vector<SettingsWhen> settings_used_when(const SolverInfo& solver, std::string_view variant) {
  const std::vector<std::string_view> used = settings_used(solver, variant);
  const auto uses = [&](std::string_view name) { return std::find(used.begin(), used.end(), name) != used.end(); };
  std::vector<SettingsWhen> out;
  for (const SettingField& field : kSettingFields) {
    if (!field.text || !uses(field.name)) continue;
    for (const std::string_view choice : field.choices.subspan(field.choices.empty() ? 0 : 1)) {
      Settings base;
      base.variant = variant;
      base.*field.text = choice;
      if (!solver.check(base).empty()) continue;
      const std::string described = solver.describe(base);
      SettingsWhen when{field.name, choice, {}};
      for (const SettingField& other : kSettingFields)
        if (!uses(other.name) && solver.describe(with_field(base, other, true)) != described)
          when.settings.push_back(other.name);
      if (!when.settings.empty()) out.push_back(std::move(when));
    }
  }
  return out;
}

const SolverInfo* find_solver(std::string_view solver_name) {
  for (const SolverInfo& s : kSolvers)
    if (s.name == solver_name) return &s;
  return nullptr;
}

std::string_view left_out_needs(std::string_view solver_name) {
  // The optional engines and their packages (CMakeLists.txt, scripts/setup.sh).
  constexpr std::array<std::array<std::string_view, 2>, 7> kOptional{{{"ode", "libode-dev"},
                                                                      {"bullet", "libbullet-dev"},
                                                                      {"siconos", "libsiconos-kernel-dev"},
                                                                      {"compliant", "libsundials-dev"},
                                                                      {"mujoco", "libmujoco-dev"},
                                                                      {"dart", "libdart-dev"},
                                                                      {"simbody", "libsimbody-dev"}}};
  if (find_solver(solver_name)) return {};
  for (const auto& [solver, package] : kOptional)
    if (solver == solver_name) return package;
  return {};
}

}  // namespace pb
