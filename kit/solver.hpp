#pragma once
// The one interface every solver implements:
//
//   Result solve(const System&, const Settings&)
//
// A solver reads no files, prints nothing and knows nothing of sweeps; it gets the
// physical system (cases/system.hpp) and plain settings, and returns plain data.
// Solvers are listed by name in the registry (solvers/registry.hpp, find_solver), which is all
// a sweep sees.

#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cases/system.hpp"

namespace pb {

enum class Status {
  ok,        // ran to t_end
  diverged,  // state grew without bound
  nan,       // a NaN or inf appeared
  step_cap,  // more steps or events than Settings::step_cap
  time_limit,   // more wall time than Settings::time_limit, or stopped (Settings::stop)
  failed,       // the solver could not go on (message says why)
  penetration,  // the reference only: a gap went below its closure tolerance (a wrong answer)
  energy,       // the reference only: the run made energy beyond round-off (a wrong answer)
};
std::string_view name(Status s);
std::optional<Status> parse_status(std::string_view text);  // the inverse of name()

// A setting of one solver's own, declared in its folder (SolverInfo::own_settings) rather than
// as a member of Settings: a number, given as `--<name>` (with '_' as '-'), held in
// Settings::own at its index in the solver's list. A new solver's setting then touches no file
// outside its folder; a flag that the chosen solver does not declare is refused.
struct OwnSetting {
  std::string_view name;
  std::string_view help;
  double fallback = 0.0;  // its value where it is not given
};
inline constexpr std::size_t kMaxOwnSettings = 4;

struct Settings {
  std::string variant;   // solver-specific variant; empty = the solver's default
  int steps = 0;         // time-steppers: steps per shortest period N (h = t_min / N); 0 = default
  double wh = 0;         // time-steppers: the step as w_max h (w_max = 2 pi / t_min); > 0 replaces steps
  // time-steppers: the step in seconds, the case's time unit (> 0 replaces steps and wh): one
  // step for every case of a study, each case's N following from it (issue 51)
  double h_s = 0;
  int steps_per_sample = 0;  // time-steppers on a record: the step rule `record` (record_step); 0 = T_min / N alone
  double theta = 0.5;    // Moreau-Jean theta
  double gamma = 0.5;    // activation look-ahead of the faithful time-steppers (fixed_step.hpp, Activation)
  double tol_scale = 1;  // event-driven: multiplies every internal tolerance
  double stiffness = 0;  // compliant: contact stiffness as the Pi term K (cases/README.md); 0 = default
  // A contact element's stiffness as the user gave it, in N/m (N/m^1.5 for the Hertz family):
  // run_point sets each case's Pi term `stiffness` from it (the unit of mass is the case's m0),
  // so one value holds across the cases of a study. A describe() names it where it is given,
  // and the Pi term beside it only where that was set too (`run --k-contact`: one case).
  double k_contact = 0;
  double rtol = 0;       // compliant with cvode: relative tolerance; 0 = default
  std::string integrator;  // compliant: cvode or newmark; empty = the solver's default
  std::string method;      // compliant with cvode: bdf or adams; empty = the solver's default
  std::string contact;     // event-driven: rigid (empty) or kelvin-voigt, the compliant model solved exactly
  double contact_steps = 0;  // mujoco: the contact time constant 1/w_c in steps h; 0 = default
  std::string command;     // external: the program to run per point, as words (docs/external.md)
  std::string name;        // external: what its rows and the report call it; empty: its command
  std::string lcp;         // siconos: the LCP solver of a scheme that does not name it, lemke or enum; empty = lemke
  double projection_tol = 0;  // siconos projections: tolerance on a violated gap over a_p/w_p^2; 0 = default
  // The solver's own settings (SolverInfo::own_settings), by index; NaN: not given.
  std::array<double, kMaxOwnSettings> own = {std::numeric_limits<double>::quiet_NaN(),
                                             std::numeric_limits<double>::quiet_NaN(),
                                             std::numeric_limits<double>::quiet_NaN(),
                                             std::numeric_limits<double>::quiet_NaN()};
  long step_cap = 0;     // 0 = the solver's own cap
  double time_limit = 0;  // seconds of wall time per run; 0 = none
  // The point's limit as it was given, which messages quote: a sweep gives each solve of a point
  // what is left of it as time_limit (0.999998 s of `--time-limit 1`). 0: time_limit is it.
  double point_time_limit = 0;
  // Set by a sweep that is being stopped: a run in progress ends as time_limit at its
  // next look at the clock. Not a setting of the solver: never part of describe().
  const std::atomic<bool>* stop = nullptr;
  bool monitor = true;   // time-steppers: measure the energy balance and restitution (StepMonitor)
  int history_samples = 0;  // > 0: record the state at this many equally spaced times
                            // (event-driven) or at every step (time-steppers)
  // The external solver in process (a Python callable, `poundbench.spectrum(set, solver=f)`):
  // given the case document, returns the answer document and sets its second argument to the
  // wall seconds of the call alone. Set by the Python module; like stop, never part of
  // describe(). Null: the external solver runs Settings::command.
  const std::function<std::string(const std::string& case_document, double& call_seconds)>* in_process = nullptr;
};

// State samples, one row per time: t, u[0..n), v[0..n), g[0..c), lambda[0..c), bodies
// left to right. lambda is a force (impulses of a step are divided by the step).
struct History {
  int n_bodies = 0;
  int n_contacts = 0;
  std::vector<double> data;  // row-major, row_size() values per row

  int row_size() const { return 1 + 2 * n_bodies + 2 * n_contacts; }
  std::size_t rows() const { return row_size() ? data.size() / static_cast<std::size_t>(row_size()) : 0; }
};

struct Result {
  Status status = Status::ok;
  std::string message;  // why a run did not finish, or notes
  double pi1 = std::numeric_limits<double>::quiet_NaN();  // max |u0| w_p^2 / a_p
  double t_max = std::numeric_limits<double>::quiet_NaN();  // time of that maximum
  long impacts = 0;         // contact closures with an approach velocity (per contact)
  long contact_phases = 0;  // entries into persistent contact (per contact)
  long steps = 0;           // time steps, or events for an event-driven solver
  double step = std::numeric_limits<double>::quiet_NaN();  // a time-stepper's fixed h
  double min_gap = std::numeric_limits<double>::infinity();  // most negative gap (penetration)
  // Energy balance: the largest value over the run of E + D - E0 - W, over
  // System::energy_scale(), where E is the mechanical energy, D what the dampers
  // dissipated and W the work of the ground load since t = 0. Exact dynamics keep it <= 0
  // (impacts only lose energy); above round-off, the solver made energy. NaN: not measured.
  double energy_excess = std::numeric_limits<double>::quiet_NaN();
  // Measured restitution -g'+ / g'- over the isolated impacts: one contact alone, its first
  // step (or event) with an impulse, approaching faster than kRestitutionFloor a_p / w_p.
  long isolated_impacts = 0;
  double restitution_low = std::numeric_limits<double>::quiet_NaN();
  double restitution_high = std::numeric_limits<double>::quiet_NaN();
  // The range is over whole contacts of elements that last (the compliant elements, MuJoCo's
  // soft contacts: -g' at the contact's end over -g' at its start), not over one step or
  // event: it then holds the model's own response to the bodies' springs and the load during
  // each contact as well as the impact law's.
  bool restitution_over_contacts = false;
  // A time-stepper's largest |g'| over the states at its step ends: h times it is one step
  // of travel at the fastest gap rate, what a velocity-level scheme may overlap (stress
  // check `gap`). NaN: not measured (the reference, or monitor off).
  double gap_rate_max = std::numeric_limits<double>::quiet_NaN();
  // Yielding (cases/README.md, "Yielding"; NaN for a system with no yielding body): body 0's
  // residual displacement over a_p / w_p^2, (1 - alpha) (u0 - z0) at t_end
  // (System::residual), and the energy its hysteresis dissipated by t_end over the work the
  // ground load did on every body (the input energy). Its ductility demand is Pi1 over
  // its Pi_y (rows/row.hpp, ductility).
  double residual = std::numeric_limits<double>::quiet_NaN();
  double hysteretic = std::numeric_limits<double>::quiet_NaN();
  // The reference's energy terms at t_end of a yielding system (NaN otherwise): the
  // ground's work `input` equals what the bodies hold (kinetic, elastic: System::energy)
  // plus what the dampers, the hysteresis of every body and the impacts took, up to the
  // round-off of the closed forms and of the quadrature of input and damped.
  struct Energies {
    double input = std::numeric_limits<double>::quiet_NaN();
    double kinetic = std::numeric_limits<double>::quiet_NaN();
    double elastic = std::numeric_limits<double>::quiet_NaN();
    double damped = std::numeric_limits<double>::quiet_NaN();
    double hysteretic = std::numeric_limits<double>::quiet_NaN();
    double impacts = std::numeric_limits<double>::quiet_NaN();
  } energies;
  // CPU seconds of the processes the solver ran (the external solver's program), which the
  // thread's own CPU clock does not see: a sweep adds them to the solve's CPU time.
  double child_cpu_seconds = 0.0;
  // The shortest contact of an element with a duration of its own (the compliant solver's
  // Newmark), in steps of the integrator: from the step end its element was first found closed
  // at, approaching faster than kRestitutionFloor a_p / w_p, to the last. NaN: no such contact,
  // or a solver whose contacts are instantaneous or whose steps are its own (CVODE).
  double contact_steps_min = std::numeric_limits<double>::quiet_NaN();
  // Whether the run can vouch for its answer, judged from its own measurements by
  // kit/verdict.hpp (every run_point judges its run): true or false for a run that ended
  // ok, empty for one that did not (its status says what happened) or that was not judged (a
  // Result straight from a solver's solve). `unresolved` says why not, criterion by criterion.
  std::optional<bool> resolved;
  std::string unresolved;
  // A solver's own reason it cannot vouch for an answer it finished (the exact Kelvin-Voigt
  // reference above the stiffness its round-off allows): the verdict counts it as unresolved.
  std::string doubt;
  History history;
  // The pounding itself, measured where impacts are counted (note_impact): the time of the
  // first impact and the largest relative approach velocity -g' at one (the gap rate before
  // it: a time-stepper's at the start of the step it closed in, seen at the step's end); NaN
  // without impacts, or from a solver that does not report them (the external programs).
  // For an element that lasts, the largest contact force over the run (per unit of m0,
  // which make_system takes as 1: times the user's m0 it is in N); NaN for rigid contact.
  double first_impact = std::numeric_limits<double>::quiet_NaN();
  double impact_velocity_max = std::numeric_limits<double>::quiet_NaN();
  double contact_force_max = std::numeric_limits<double>::quiet_NaN();
  // The external solver's: the program's own time for its solve (the answer's solve_seconds; a
  // Python callable's call, timed around it), beside the sweep's timing of the whole exchange.
  // NaN: not reported.
  double solve_seconds = std::numeric_limits<double>::quiet_NaN();
  // The wall seconds a persistent program took to start, from its spawn to its ready line, on
  // the one point whose solve started it (NaN on every other): the sweep takes it off that
  // point's seconds, so the start-up is reported once, apart from any solve.
  double startup_seconds = std::numeric_limits<double>::quiet_NaN();
  // A fixed-step run's estimated relative error of Pi1, and of impact_velocity_max, by
  // Richardson from a companion solve at twice the step (sweep/sweep.hpp, run_point's
  // ErrorEstimate): |x(h) - x(2h)| / (2^p - 1) / |x(h)|, p the solver's SolverInfo::step_order.
  // NaN: not estimated (not asked for, no fixed step, a solver of no known order, or no impact
  // in one of the two solves for the velocity's).
  double error_estimate = std::numeric_limits<double>::quiet_NaN();
  double error_estimate_velocity = std::numeric_limits<double>::quiet_NaN();
};

// An impact at time t approaching at -rate > 0: what every solver's impact count notes.
inline void note_impact(Result& r, double t, double rate) {
  if (!(r.first_impact <= t)) r.first_impact = t;
  if (!(r.impact_velocity_max >= -rate)) r.impact_velocity_max = -rate;
}

// Slower approaches are not counted as isolated impacts: there a step's smooth forces
// change the relative velocity as much as the impact does.
inline constexpr double kRestitutionFloor = 1e-3;

// The fixed step of a time-stepper: settings.h_s if given, else w_max h = settings.wh if given,
// else t_min / N with N = settings.steps or the solver's default.
// With Settings::steps_per_sample = k > 0 on a record, that step becomes record_step's.
inline double time_step(const System& s, const Settings& settings, int default_steps) {
  const double h = settings.h_s > 0.0  ? settings.h_s
                   : settings.wh > 0.0 ? settings.wh * s.t_min / (2.0 * std::numbers::pi)
                                       : s.step(settings.steps > 0 ? settings.steps : default_steps);
  return settings.steps_per_sample > 0 && s.pulse.record ? record_step(*s.pulse.record, h, settings.steps_per_sample) : h;
}

// Settings::steps_per_sample on a case whose load is not a record: the reason it is refused
// ("" when it is fine). A pulse has no samples: its step stays T_min / N.
std::string step_rule_problem(const System& system, const Settings& settings);

// The step bound of every fixed step (issue 33): a step may be at most the pulse period
// T_p = 2 pi / w_p (w_p h <= 2 pi), so that a run takes at least one step per pulse. A
// longer step steps over the load it is meant to follow (an engine that samples a_g at its
// step ends may never see it), and far beyond it a run has no step at all: --wh 1e11 said
// ok with zero steps and Pi1 = 0, and Siconos died of SIGFPE from about 1e293. N = steps
// always meets it (h = T_min / N, T_min <= T_p); w_max h = wh meets it for wh <= 2 pi, and
// beyond where the bodies are faster than the pulse. "" when h is within it, else the
// reason, naming h and T_p.
std::string step_problem(const System& system, double h);
// A result that step_problem refused (status failed, its message): a run that never started,
// which a study leaves out of its cell rather than count as a scheme's failure.
inline constexpr std::string_view kStepBoundMessage = "step: h = ";
inline bool beyond_step_bound(const Result& r) {
  return r.status == Status::failed && r.message.starts_with(kStepBoundMessage) &&
         r.message.find("longer than the pulse period") != std::string::npos;
}

// Checks Settings::steps and Settings::wh for a time-stepper; "" when they are fine.
std::string check_step(const Settings& settings, int default_steps);
// Checks Settings::theta and gamma of a theta-method (moreau-jean, Siconos' MoreauJeanOSI).
std::string check_theta_method(const Settings& settings);
// Checks Settings::gamma, the look-ahead of a time-stepper that predicts its contacts.
std::string check_gamma(const Settings& settings);
// Checks Settings::step_cap and time_limit: the registry applies it to every solver's check
// (solvers/registry.cpp), so a solver's own check leaves them alone.
std::string check_limits(const Settings& settings);

using SolveFn = Result (*)(const System&, const Settings&);

// The buildings scene (cases/buildings.hpp; its result: kit/buildings_result.hpp).
struct BuildingModel;
namespace buildings {
struct BuildingsResult;
}
using BuildingsSolveFn = buildings::BuildingsResult (*)(const BuildingModel&, const Settings&);

// A variant of a solver (Settings::variant) and one line on what it is. Each solver lists
// the names its solve() knows, its default first: the one the empty name runs (the
// reference's default has no other name).
struct VariantInfo {
  std::string_view name;
  std::string summary;
};

// The reference of a setting's own model, where that model is not rigid contact (a compliant
// element): the same model solved exactly or far tighter, by the solver named here with these
// settings, so that a study can tell the setting's integration error from its model's error
// against the rigid reference.
struct ModelReference {
  std::string_view solver;
  Settings settings;
};

// A run that failed before it had an answer, and why.
Result failed(std::string message);

// The run of a yielding system (System::yields) by a solver whose engine owns the bodies'
// springs and cannot take the bilinear law: failed, with "yielding: " and why in its
// message, never an elastic answer in place of the yielding one.
Result yielding_refused(std::string_view why);

struct SolverInfo {
  std::string_view name;     // as given to --solver
  std::string_view summary;  // one line for --help
  SolveFn solve;
  // The settings that matter to this solver, as "key=value;key=value" for result rows.
  std::string (*describe)(const Settings&);
  // Checks settings before a run; returns "field: reason" or an empty string.
  std::string (*check)(const Settings&);
  // Its variants, the default first (`poundbench solvers`); every registered solver has
  // them (null only in a test's stand-in solver).
  std::vector<VariantInfo> (*variants)() = nullptr;
  // How far a rerun's Pi1 may move from its stored baseline (relative): round-off only,
  // on another compiler or libm. The registry says why per solver.
  double baseline_tolerance = 1e-9;
  // The solver every error is measured against (exactly one).
  bool reference = false;
  // The reference of a setting's own model (nullopt: the rigid reference is its model's, or
  // the setting is its model's reference itself); null: nullopt for every setting.
  std::optional<ModelReference> (*model_reference)(const Settings&) = nullptr;
  // Solved once per point: the timed solve carries Settings::monitor as the run asks and is
  // the row's measurement too, with no monitored pass more (the external solver: a second
  // pass ran the user's program twice per point; it measures what it can either way).
  bool one_pass = false;
  // The order p of Pi1 in the step that the error estimate assumes (Result::error_estimate),
  // for a run with a fixed step (Result::step finite); 0: no estimate (a solver without a fixed
  // step, or whose order poundbench does not know: the external programs'). A per-solver fact
  // from the registry: 1 for every fixed-step solver, measured (solvers/registry.cpp says how).
  double step_order = 0.0;
  // The contact-law family of a setting: true where its contact is a Hertz-type element, whose
  // stiffness is in N/m^1.5 (a physical k_contact maps to the Pi term through a length scale:
  // cases/README.md, "Contact stiffness"); null: linear elements, or rigid contact.
  bool (*hertz_contact)(const Settings&) = nullptr;
  // The settings of the solver's own (OwnSetting), at most kMaxOwnSettings.
  std::span<const OwnSetting> own_settings{};
  // Its solve of the buildings scene; null: it refuses the scene (by name, in one line).
  BuildingsSolveFn solve_buildings = nullptr;
  // The fields of kit/settings_fields.hpp that its buildings solve reads (the limits
  // step_cap and time_limit included where it honours them); any other given is refused.
  std::span<const std::string_view> buildings_settings{};
};

// The index of the own setting `name` in a solver's list of them, if it declares it.
inline std::optional<std::size_t> own_setting_index(std::span<const OwnSetting> own, std::string_view name) {
  for (std::size_t i = 0; i < own.size(); ++i)
    if (own[i].name == name) return i;
  return std::nullopt;
}

// Own setting i of a run, from the solver's list of them: as given, else its fallback.
inline double own_value(const Settings& settings, std::span<const OwnSetting> own, std::size_t i) {
  return std::isnan(settings.own[i]) ? own[i].fallback : settings.own[i];
}

}  // namespace pb
