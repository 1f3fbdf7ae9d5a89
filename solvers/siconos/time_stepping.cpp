// The time-stepping variants: Siconos' TimeStepping with MoreauJeanOSI(theta, gamma) and an
// LCP at the velocity level, one step at a time, so that every step is seen: the state, the
// impulses, the index set Siconos chose and the path its LCP driver took.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "solvers/monitor.hpp"
#include "solvers/siconos/model.hpp"

namespace pb::siconos {

namespace {

// Per contact, what the counts need from one step to the next (contact j at index j).
struct Contacts {
  std::vector<char> active;    // in the index set of the last step
  std::vector<char> entering;  // ... and not in the one of the step before
  std::vector<char> pushed;    // positive impulse in the last step
  std::vector<char> in_phase;  // in a run of >= 2 steps with a positive impulse
  std::vector<double> force;   // impulse of the last step over h (History's lambda)
  explicit Contacts(std::size_t nc) : active(nc), entering(nc), pushed(nc), in_phase(nc), force(nc) {}
};

struct Tally {
  double u_max = 0.0;
  long k_max = 0;
  double g_min = 0.0;
  long impacts = 0, phases = 0;

  void state(const System& s, const State& st, long k) {
    const double u = std::abs(st.u[static_cast<std::size_t>(s.ref)]);
    if (u > u_max) {
      u_max = u;
      k_max = k;
    }
    for (double g : st.g) g_min = std::min(g_min, g);
  }
};

void count(const engine::LcpCall& call, LcpPaths& paths) {
  if (!call.called) return;
  ++paths.calls;
  if (call.q_nonnegative)
    ++paths.trivial;
  else if (call.rows == 1)
    ++paths.one_row;
  else
    ++paths.solver;
  if (call.counter_written) ++paths.written;
}

std::string paths_message(const LcpPaths& p, bool enumeration) {
  std::ostringstream out;
  out << "lcp: " << p.calls << " calls: " << p.trivial << " with q >= 0 (z = 0, no solver), " << p.one_row
      << " of one row (z = -q/M, no solver), " << p.solver << " by " << (enumeration ? "enumeration" : "Lemke");
  return out.str();
}

}  // namespace

Result run_time_stepping(const System& sys, const Settings& set, bool enumeration, LcpPaths* paths_out) {
  const double h = time_step(sys, set, kDefaultSteps);
  if (!(h > 0.0) || !std::isfinite(h) || !(sys.t_end / h < 1e18))
    return stopped(Status::failed, "step: h = " + std::to_string(h) + " is not a usable step");
  if (std::string bad = check_system(sys); !bad.empty()) return stopped(Status::failed, bad);
  const long n = step_count(sys.t_end, h);
  const long cap = set.step_cap > 0 ? set.step_cap : kDefaultStepCap;
  if (n > cap) {
    Result r = stopped(Status::step_cap,
                       "the run needs " + std::to_string(n) + " steps, more than the cap " + std::to_string(cap));
    r.step = h;
    return r;
  }

  const Units units = units_of(sys);
  const double hs = h / units.time;
  // Siconos' horizon half a step past the last step, so that round-off cannot drop it.
  engine::TimeStepper run(model_spec(sys, h, (static_cast<double>(n) + 0.5) * h), hs, set.theta, set.gamma,
                          enumeration);
  const int nc = sys.n_contacts();
  const double force_unit = units.velocity() / h;  // of an impulse in Siconos' units, per unit mass

  Result res;
  res.step = h;
  State st(sys);
  st.read(run, sys, units);
  Contacts c(st.g.size());
  Tally t;
  t.state(sys, st, 0);
  std::optional<StepMonitor> monitor;
  if (set.monitor) monitor.emplace(sys);
  const bool recording = set.history_samples > 0;
  if (recording) {
    res.history.n_bodies = sys.n_bodies();
    res.history.n_contacts = nc;
    res.history.data.reserve(static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(res.history.row_size()));
    record(0.0, st, c.force, res.history.data);
  }
  LcpPaths paths;
  const char* stop_reason = nullptr;
  Deadline deadline(set);
  long k = 0;
  while (k < n) {
    // The index set of this step, chosen by Siconos from the state at t_k.
    for (int j = 0; j < nc; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      const bool active = run.active(j);
      c.entering[jj] = active && !c.active[jj] ? 1 : 0;
      c.active[jj] = active ? 1 : 0;
    }
    bool stepped = false;
    try {
      stepped = run.step();
    } catch (const std::exception& e) {
      res.status = Status::failed;
      res.message = std::string("Siconos: ") + e.what() + " (at step " + std::to_string(k + 1) + ")";
      break;
    }
    if (!stepped) {
      res.status = Status::failed;
      res.message = "Siconos ended the run at step " + std::to_string(k) + " of " + std::to_string(n);
      break;
    }
    ++k;
    count(run.last_lcp(), paths);
    if (run.last_lcp().info != 0) {
      res.status = Status::failed;
      res.message = "Siconos' LCP solver returned info " + std::to_string(run.last_lcp().info) + " at step " +
                    std::to_string(k);
      break;
    }
    for (int j = 0; j < nc; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      const double impulse = run.impulse(j);
      c.force[jj] = impulse * force_unit;
      const bool pushing = impulse > 0.0;
      if (c.entering[jj] && st.rate[jj] < 0.0) ++t.impacts;  // st: still the state at t_k
      if (pushing && c.pushed[jj] && !c.in_phase[jj]) {
        ++t.phases;
        c.in_phase[jj] = 1;
      }
      if (!pushing) c.in_phase[jj] = 0;
      c.pushed[jj] = pushing ? 1 : 0;
    }
    st.read(run, sys, units);
    // Before the divergence test: a diverging run's energy excess shows the growth.
    const double t0 = static_cast<double>(k - 1) * h, t1 = static_cast<double>(k) * h;
    if (monitor) monitor->step(h, sys.pulse.mean(t0, t1), st.u.data(), st.v.data(), c.pushed.data());
    if (!st.finite()) {
      res.status = Status::nan;
      stop_reason = "non-finite state";
      break;
    }
    if (const char* why = runaway(sys, st)) {
      res.status = Status::diverged;
      stop_reason = why;
      break;
    }
    t.state(sys, st, k);
    if (recording) record(t1, st, c.force, res.history.data);
    if (k < n && deadline.passed(k)) {
      res.status = Status::time_limit;
      res.message = deadline.reason() + " at t = " + std::to_string(t1);
      break;
    }
  }

  res.steps = k;
  res.impacts = t.impacts;
  res.contact_phases = t.phases;
  res.min_gap = t.g_min < 0.0 ? t.g_min : std::numeric_limits<double>::infinity();
  if (monitor) monitor->finish(res);
  if (paths_out) *paths_out = paths;
  if (stop_reason) {
    std::ostringstream msg;
    msg << stop_reason << " at step " << k << " (t = " << static_cast<double>(k) * h
        << ", w_max h = " << 2.0 * std::numbers::pi * h / sys.t_min << ")";
    res.message = msg.str();
  }
  if (res.status != Status::ok) return res;
  res.message = paths_message(paths, enumeration);
  res.pi1 = sys.pi1(t.u_max);
  res.t_max = static_cast<double>(t.k_max) * h;
  return res;
}

}  // namespace pb::siconos
