#pragma once
// The shell around every fixed-step solver, written once (as Siconos' TimeStepping is one
// loop with integrators plugged in). It owns what every time-stepper shares: the step h
// and the step count, the step cap, the start state, counting impacts and contact phases,
// the energy monitor, the history, divergence, the deadline and the final Result. An
// engine (ODE, Bullet, Siconos' time-stepping) supplies only how to take one step and what
// it saw, through StepEngine. The stages of a run, in order:
//
//   plan_steps   h and n from the settings; the start state and the step cap checked
//   run_steps    per step: engine step -> contacts tallied -> state finite? -> monitor ->
//                diverged? -> state tallied -> history row -> deadline
//   finish       counts, the message of a run that stopped, the engine's notes, Pi1
//
// Moreau-Jean keeps its own fixed-size inner loop (there a call per step would cost as
// much as the step) and shares the rest: plan_steps, StepTally, finish_steps, runaway.
//
// Rejected: a template over the engine type. The engines' steps cost microseconds, so one
// virtual call per step is free, and the shell then lives in one .cpp file.

#include <algorithm>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "cases/system.hpp"
#include "kit/named_values.hpp"
#include "kit/solver.hpp"

namespace pb {

// Every time-stepper's defaults: N when neither Settings::steps nor wh is given (64 steps
// per shortest period: Moreau-Jean's Pi1 error is ~1e-3 there on the paper set), and the
// step cap when Settings::step_cap is 0 (1e8 steps: seconds to minutes of any engine).
inline constexpr int kDefaultSteps = 64;
inline constexpr long kDefaultStepCap = 100'000'000;

// Which contacts take part in the step from t_k, from each contact's gap g and gap rate g'
// at t_k (System::gap, gap_rate):
//   predicted  g + gamma h g' <= 0: the gap predicted gamma h ahead at the rate of t_k is
//              closed (gamma = Settings::gamma, default 1/2: the gap at mid-step). The
//              Moreau-Jean rule, and so that of every faithful time-stepper: moreau-jean
//              (in its own fixed-size loop, stepper.hpp and dynamic.cpp, the same arithmetic),
//              Siconos' MoreauJeanOSI (which applies it itself), and the faithful variants of
//              ODE and Bullet, which call active(). One rule, so that a work-precision study
//              compares the solvers and not when their contacts start.
//   overlap    g <= 0: the bodies touch or overlap, which is when an engine's collision
//              detection reports a contact (the engines' default variants, bullet si-overlap).
// A contact made ahead of time (g > 0) is a velocity-level constraint only: each engine is
// given a depth of zero for it, so that nothing pulls the bodies across the gap or pushes
// them apart beyond Newton's law (solvers/ode/README.md, solvers/bullet/README.md).
enum class Activation { predicted, overlap };

// gamma_h = Settings::gamma times h, formed once per run as moreau-jean forms it.
inline bool active(Activation rule, double g, double rate, double gamma_h) {
  return rule == Activation::predicted ? g + gamma_h * rate <= 0.0 : g <= 0.0;
}

// The rule's name, and gamma where the rule uses it, for describe().
void add_activation(NamedValues& out, std::string_view key, Activation rule, const Settings& set);

// Checks Settings::gamma where the rule uses it; "" when it is fine.
std::string check_activation(Activation rule, const Settings& set);

// The step of a run and how many steps reach t_end.
struct StepPlan {
  double h = 0.0;
  long n = 0;
};

// The first step count whose end reaches t_end, to within 1e-9 of a step (so that
// t_end = n h up to round-off does not add a step).
long step_count(double t_end, double h);

// h = time_step(settings), n = step_count. A Result with a status other than ok (and its
// step) when the run cannot start: bad step settings, a start state of the wrong size, a
// step that is not usable, more steps than the cap (the solver's own when step_cap is 0).
Result plan_steps(const System& sys, const Settings& set, int default_steps, long default_cap, StepPlan& plan);

// steps = N or wh = X, whichever fixed the step: the first of a time-stepper's describe().
void add_step(NamedValues& out, const Settings& set, int default_steps);

// Counts over a run's steps, as every time-stepper reports them.
struct StepTally {
  double u_max = 0.0;  // largest |u_ref| over the states
  long k_max = 0;      // its step
  double g_min = 0.0;  // most negative gap (0 if none)
  long impacts = 0;    // contacts whose constraint entered a step while approaching
  long phases = 0;     // runs of >= 2 consecutive steps with a positive contact force
  double first_impact = std::numeric_limits<double>::quiet_NaN();  // Result::first_impact
  double fastest_impact = 0.0;                                      // Result::impact_velocity_max

  // An impact seen at time t (a step's end), approaching at -rate > 0 at the step's start.
  // Called on impacts only: the step loop's cost does not change (bench/, callgrind).
  void impact(double t, double rate) {
    ++impacts;
    if (!(first_impact <= t)) first_impact = t;
    fastest_impact = std::max(fastest_impact, -rate);
  }

  // The state at step k.
  void state(const System& sys, long k, const double* u);
};

// What every engine reports after each step (and holds at the start): the state, and per
// contact the force over the step (impulse / h, History's lambda) and whether its
// constraint was new in that step.
struct StepOutput {
  std::vector<double> u, v;   // per body
  std::vector<double> force;  // per contact
  std::vector<char> entered;  // per contact
  explicit StepOutput(const System& sys);
};

// How a step of an engine went: `taken`; `refused` (the step did not happen: the run stops
// at t_k); `taken_then_stop` (the step happened and counts, but its outcome is not to be
// used: the run stops at t_k+1). When it stops, the engine has set res.status and message.
enum class StepOutcome { taken, refused, taken_then_stop };

// Step k (0-based) of `engine` happened, but its Dantzig LCP (ODE's dLCP, which DART carries
// too) gave up on a degenerate pivot: the step's contact `unknowns` ("forces", "impulses")
// are wrong, and the run fails there.
StepOutcome dantzig_gave_up(std::string_view engine, long k, std::string_view unknowns, Result& res);

class StepEngine {
 public:
  virtual ~StepEngine() = default;
  // From t_k = k h to t_k+1, leaving out() at t_k+1.
  virtual StepOutcome step(long k, Result& res) = 0;
  // Engine notes added to every result (fallbacks, library messages, LCP paths), and any
  // check that can fail only at the end. Called once, after the counts are in res.
  virtual void finish(Result& res) { (void)res; }
  // True for an engine whose contacts are elements with a duration of their own (a nonzero
  // force at each step end while closed): the shell counts the steps each lasts
  // (Result::contact_steps_min, kit/verdict.hpp). A rigid contact acts within one step by
  // design, and MuJoCo's soft one lasts a number of steps its calibration fixes.
  virtual bool contacts_have_duration() const { return false; }
  const StepOutput& out() const { return out_; }

 protected:
  explicit StepEngine(const System& sys) : out_(sys) {}
  StepOutput out_;
};

// The start state of a System (rest when it gives none), one value per body.
std::vector<double> start_u(const System& sys);
std::vector<double> start_v(const System& sys);

// Runs the engine over plan.n steps of plan.h from its out() at t = 0.
Result run_steps(const System& sys, const Settings& set, const StepPlan& plan, StepEngine& engine);

// Counts, status message and Pi1 from the tally once a loop has stopped at step k. A nan or
// diverged run's message says what stopped it (res.message if the engine said, else `why`,
// else the default wording) and where.
void finish_steps(const System& sys, const StepTally& tally, long k, double h, const char* why, Result& res);

}  // namespace pb
