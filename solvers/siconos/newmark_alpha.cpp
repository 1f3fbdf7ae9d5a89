// The newmark-alpha variant: Siconos' EventDriven simulation with NewMarkAlphaOSI, the
// nonsmooth generalized-alpha scheme (Chen, Acary, Virlez, Bruls): a fixed step h, Newton
// iterations on each step with a position-level LCP of the closed contacts, and events
// located inside a step where a gap closes or a contact force vanishes.
//
// In Siconos 4.4 it cannot run these cases: NewMarkAlphaOSI::computeW negates a
// LagrangianLinearTIDS's K and C in place on every call (`*K *= -1.0`, `*C *= -1.0`), and
// EventDriven::newtonSolve calls it once per Newton iteration, so the forces flip sign from one
// iteration to the next and the residual never falls below its tolerance. newtonSolve has no
// exit but convergence: past its iteration limit it prints a warning and iterates on. The run
// stops it (engine::NewmarkAlphaRun) after kNewtonOverrun times that limit, and ends as failed,
// with the iterations made and how many of them changed the sign of body 0's K: the cause,
// measured on the library that is linked. A future Siconos runs through the same code.

#include <cmath>
#include <limits>
#include <sstream>

#include "kit/fixed_step.hpp"
#include "kit/run_limits.hpp"
#include "solvers/siconos/model.hpp"

namespace pb::siconos {

namespace {

// The start of every message of a run that Siconos 4.4 could not take through (a substring the
// solver contract's facts name).
constexpr const char* kFails = "NewMarkAlphaOSI with EventDriven fails: ";

std::string newton_loop_message(const engine::NewmarkAlphaRun::NewtonLoop& loop, double time_unit) {
  std::ostringstream msg;
  msg << kFails << "EventDriven::newtonSolve does not converge: " << loop.iterations
      << " Newton iterations in the step from t = " << loop.time * time_unit << " (its own limit is "
      << loop.siconos_limit << "; past it Siconos warns and iterates on, without end). NewMarkAlphaOSI::computeW "
      << "changed the sign of body 0's stiffness K in " << loop.k_sign_flips << " of them: it negates the "
      << "LagrangianLinearTIDS's K and C in place on every call";
  return msg.str();
}

// Events in a row at one time after which the run counts as stalled: an impact and the
// contact events it starts take a handful.
constexpr long kStalledEvents = 1000;

std::string changed_model_message(int body, double k, double c, const System& sys, const Units& units, long events,
                                  double now) {
  const Body& b = sys.bodies[static_cast<std::size_t>(body)];
  std::ostringstream msg;
  msg << kFails << "after " << events << " events (t = " << now << "), Newton converged on a changed system: body "
      << body << " holds K = " << k / (units.time * units.time) << ", C = " << c / units.time << " instead of "
      << b.k << ", " << b.c << " (NewMarkAlphaOSI::computeW negates the LagrangianLinearTIDS's K and C in place on "
      << "every call)";
  return msg.str();
}

}  // namespace

Result run_newmark_alpha(const System& sys, const Settings& set) {
  if (std::string bad = check_system(sys); !bad.empty()) return stopped(Status::failed, bad);
  StepPlan plan;
  if (Result r = plan_steps(sys, set, kDefaultSteps, kDefaultStepCap, plan); r.status != Status::ok) return r;
  const Units units = units_of(sys);
  Deadline deadline(set);
  const double horizon = (static_cast<double>(plan.n) + 0.5) * plan.h;
  engine::NewmarkAlphaRun run(model_spec(sys, plan.h, horizon), plan.h / units.time, kRhoInfinity, kNewtonOverrun,
                              &deadline_passed, &deadline);

  const int nc = sys.n_contacts();
  const auto ref = static_cast<std::size_t>(sys.ref);
  Result res;
  res.step = plan.h;
  State st(sys), before(sys);
  st.read(run, sys, units);
  std::vector<double> force(st.g.size());
  double u_max = std::abs(st.u[ref]), t_max = 0.0, g_min = 0.0;
  long impacts = 0, events = 0;
  const bool recording = set.history_samples > 0;
  if (recording) {
    res.history.n_bodies = sys.n_bodies();
    res.history.n_contacts = nc;
    record(0.0, st, force, res.history.data);
  }
  double t_last = 0.0;
  long stalled = 0;  // events in a row that did not advance the time
  while (run.has_next()) {
    before = st;
    try {
      run.advance();
    } catch (const engine::NewmarkAlphaRun::NewtonLoop& loop) {
      res.status = loop.stopped ? Status::time_limit : Status::failed;
      res.message = loop.stopped ? deadline.reason() + " at t = " + std::to_string(loop.time * units.time)
                                 : newton_loop_message(loop, units.time);
      break;
    } catch (const std::exception& e) {
      res.status = Status::failed;
      res.message = std::string("Siconos: ") + e.what() + " (after " + std::to_string(events) + " events)";
      break;
    }
    ++events;
    st.read(run, sys, units);
    const double now = run.time() * units.time;
    // The system itself must be the case's: a step after which Newton converged on a model
    // whose K or C the integrator changed is no answer to the case.
    double k = 0.0, c = 0.0;
    if (const int i = run.changed_body(k, c); i >= 0) {
      res.status = Status::failed;
      res.message = changed_model_message(i, k, c, sys, units, events, now);
      break;
    }
    stalled = now > t_last ? 0 : stalled + 1;
    t_last = std::max(t_last, now);
    if (stalled >= kStalledEvents) {
      res.status = Status::failed;
      res.message = std::string(kFails) + "EventDriven makes no progress: " + std::to_string(stalled) +
                    " events in a row at t = " + std::to_string(now) + " (an event that its processing repeats " +
                    "without end)";
      break;
    }
    if (deadline.passed(events)) {
      res.status = Status::time_limit;
      res.message = deadline.reason() + " at t = " + std::to_string(now);
      break;
    }
    res.status = state_end(sys, st.finite(), st.u.data(), st.v.data(), now, res.message);
    if (res.status != Status::ok) break;
    if (std::abs(st.u[ref]) > u_max) {
      u_max = std::abs(st.u[ref]);
      t_max = now;
    }
    for (int j = 0; j < nc; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      if (run.impulse(j) > 0.0 && before.rate[jj] < 0.0) {
        ++impacts;
        note_impact(res, now, before.rate[jj]);
      }
      force[jj] = run.force(j) * units.length / (units.time * units.time);
      g_min = std::min(g_min, st.g[jj]);
    }
    if (recording) record(now, st, force, res.history.data);
  }
  res.steps = events;
  res.impacts = impacts;
  res.min_gap = g_min < 0.0 ? g_min : std::numeric_limits<double>::infinity();
  if (res.status != Status::ok) return res;
  std::ostringstream msg;
  msg << "newton: " << run.newton_iterations() << " iterations over " << events << " events";
  res.message = msg.str();
  res.pi1 = sys.pi1(u_max);
  res.t_max = t_max;
  return res;
}

}  // namespace pb::siconos
