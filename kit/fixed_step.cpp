#include "kit/fixed_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "kit/monitor.hpp"
#include "kit/run_limits.hpp"

namespace pb {

namespace {

Result stopped(Status status, std::string message, double h) {
  Result r;
  r.status = status;
  r.message = std::move(message);
  r.step = h;
  return r;
}

bool finite(const StepOutput& out) {
  for (std::size_t i = 0; i < out.u.size(); ++i)
    if (!std::isfinite(out.u[i]) || !std::isfinite(out.v[i])) return false;
  return true;
}

// One history row: t, u, v, g, lambda (History in kit/solver.hpp).
void record(const System& sys, double t, const StepOutput& out, std::vector<double>& rows) {
  rows.push_back(t);
  rows.insert(rows.end(), out.u.begin(), out.u.end());
  rows.insert(rows.end(), out.v.begin(), out.v.end());
  for (int j = 0; j < sys.n_contacts(); ++j) rows.push_back(sys.gap(j, out.u.data()));
  rows.insert(rows.end(), out.force.begin(), out.force.end());
}

// Impacts and contact phases of the step just taken; rate_before holds the gap rates at
// its start. A phase is counted once, when a second consecutive step pushes. For an engine
// whose contacts last (StepEngine::contacts_have_duration), also each contact's duration in
// step ends with a nonzero force, from one that entered approaching faster than `floor`.
class ContactTally {
 public:
  ContactTally(std::size_t nc, bool durations, double floor)
      : pushed_(nc), in_phase_(nc), run_(durations ? nc : 0, -1), floor_(floor) {}
  // t_end: the end of the step, where an impact of it is first seen closed.
  void step(const StepOutput& out, const std::vector<double>& rate_before, StepTally& t, double t_end) {
    for (std::size_t j = 0; j < run_.size(); ++j) {
      if (out.entered[j]) run_[j] = rate_before[j] < -floor_ ? 0 : -1;
      if (run_[j] < 0) continue;
      if (out.force[j] != 0.0) {
        ++run_[j];
        force_max_ = std::max(force_max_, out.force[j]);
      } else {  // ended
        const double steps = static_cast<double>(run_[j]);
        if (!(shortest_ <= steps)) shortest_ = steps;  // NaN: the first
        run_[j] = -1;
      }
    }
    for (std::size_t j = 0; j < pushed_.size(); ++j) {
      if (out.entered[j] && rate_before[j] < 0.0) t.impact(t_end, rate_before[j]);
      const bool push = out.force[j] > 0.0;
      if (push && pushed_[j] && !in_phase_[j]) {
        ++t.phases;
        in_phase_[j] = 1;
      }
      if (!push) in_phase_[j] = 0;
      pushed_[j] = push ? 1 : 0;
    }
  }
  const char* pushed() const { return pushed_.data(); }
  // The largest force of a contact that lasts (NaN: durations not counted; 0: no contact).
  double force_max() const {
    return run_.empty() ? std::numeric_limits<double>::quiet_NaN() : force_max_;
  }
  // The shortest finished contact in steps (NaN: none, or durations not counted).
  double shortest() const { return shortest_; }

 private:
  std::vector<char> pushed_, in_phase_;  // per contact, in the last step
  std::vector<long> run_;                // per contact: step ends closed so far, -1 not counted
  double floor_;
  double shortest_ = std::numeric_limits<double>::quiet_NaN();
  double force_max_ = 0.0;
};

}  // namespace

long step_count(double t_end, double h) { return std::max(1L, static_cast<long>(std::ceil(t_end / h - 1e-9))); }

Result plan_steps(const System& sys, const Settings& set, int default_steps, long default_cap, StepPlan& plan) {
  plan = {};
  const double h = time_step(sys, set, default_steps);
  const auto nb = ix(sys.n_bodies());
  if ((!sys.u_start.empty() && sys.u_start.size() != nb) || (!sys.v_start.empty() && sys.v_start.size() != nb))
    return stopped(Status::failed, "start state: needs one u and one v per body (or none: rest)", h);
  if (!(h > 0.0) || !std::isfinite(h) || !(sys.t_end / h < 1e18))
    return stopped(Status::failed,
                   "step: h = " + std::to_string(h) + " is not a usable step for t_end = " + std::to_string(sys.t_end),
                   h);
  if (std::string bad = step_problem(sys, h); !bad.empty()) return stopped(Status::failed, bad, h);
  if (std::string bad = step_rule_problem(sys, set); !bad.empty()) return stopped(Status::failed, bad, h);
  const long n = step_count(sys.t_end, h);
  const long cap = set.step_cap > 0 ? set.step_cap : default_cap;
  if (n > cap)
    return stopped(Status::step_cap,
                   "the run needs " + std::to_string(n) + " steps, more than the cap " + std::to_string(cap), h);
  plan = {h, n};
  Result ok;
  ok.step = h;
  return ok;
}

void add_step(NamedValues& out, const Settings& set, int default_steps) {
  if (set.h_s > 0.0)
    out.add("h_s", set.h_s);
  else if (set.wh > 0.0)
    out.add("wh", set.wh);
  else
    out.add("steps", set.steps > 0 ? set.steps : default_steps);
  if (set.steps_per_sample > 0) out.add("steps_per_sample", set.steps_per_sample);
}

void add_activation(NamedValues& out, std::string_view key, Activation rule, const Settings& set) {
  out.add(key, rule == Activation::predicted ? "predicted" : "overlap");
  if (rule == Activation::predicted) out.add("gamma", set.gamma);
}

std::string check_activation(Activation rule, const Settings& set) {
  return rule == Activation::predicted ? check_gamma(set) : std::string();
}

void StepTally::state(const System& sys, long k, const double* u) {
  const double a = std::abs(u[ix(sys.ref)]);
  if (a > u_max) {
    u_max = a;
    k_max = k;
  }
  for (int j = 0; j < sys.n_contacts(); ++j) g_min = std::min(g_min, sys.gap(j, u));
}

StepOutput::StepOutput(const System& sys)
    : u(start_u(sys)), v(start_v(sys)), force(ix(sys.n_contacts()), 0.0), entered(ix(sys.n_contacts()), 0) {}

std::vector<double> start_u(const System& sys) {
  return sys.u_start.empty() ? std::vector<double>(ix(sys.n_bodies()), 0.0) : sys.u_start;
}
std::vector<double> start_v(const System& sys) {
  return sys.v_start.empty() ? std::vector<double>(ix(sys.n_bodies()), 0.0) : sys.v_start;
}

Result run_steps(const System& sys, const Settings& set, const StepPlan& plan, StepEngine& engine) {
  const double h = plan.h;
  const long n = plan.n;
  const int nc = sys.n_contacts();
  const StepOutput& out = engine.out();
  Result res;
  res.step = h;
  StepTally tally;
  tally.state(sys, 0, out.u.data());
  ContactTally contacts(ix(nc), engine.contacts_have_duration(), kRestitutionFloor * sys.a_p / sys.pulse.w);
  std::vector<double> rate(ix(nc));
  std::optional<StepMonitor> monitor;
  // The monitor's energy is the elastic k u^2 / 2: a yielding body's hysteresis is no part
  // of it, so its balance would be wrong there (energy_excess stays NaN: not measured).
  if (set.monitor && !sys.yields()) monitor.emplace(sys);
  LoadCursor load(sys.pulse);  // the monitor's step means: O(1) a step on a record
  std::vector<double>* rows = set.history_samples > 0 ? &res.history.data : nullptr;
  if (rows) {
    res.history.n_bodies = sys.n_bodies();
    res.history.n_contacts = nc;
    rows->reserve(static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(res.history.row_size()));
    record(sys, 0.0, out, *rows);
  }

  const char* why = nullptr;  // what stopped a nan or diverged run
  Deadline deadline(set);
  long k = 0;
  while (k < n) {
    for (int j = 0; j < nc; ++j) rate[ix(j)] = sys.gap_rate(j, out.v.data());
    const StepOutcome outcome = engine.step(k, res);
    if (outcome == StepOutcome::refused) break;
    ++k;
    contacts.step(out, rate, tally, static_cast<double>(k) * h);
    if (outcome == StepOutcome::taken_then_stop) break;
    if (!finite(out)) {
      res.status = Status::nan;
      why = "non-finite state";
      break;
    }
    // Before the divergence test: a diverging run's energy excess shows the growth.
    if (monitor) {
      const double t0 = static_cast<double>(k - 1) * h, t1 = static_cast<double>(k) * h;
      monitor->step(h, load.mean(t0, t1), out.u.data(), out.v.data(), contacts.pushed());
    }
    if ((why = runaway(sys, out.u.data(), out.v.data()))) {
      res.status = Status::diverged;
      break;
    }
    tally.state(sys, k, out.u.data());
    if (rows) record(sys, static_cast<double>(k) * h, out, *rows);
    if (k < n && deadline.passed(k)) {
      res.status = Status::time_limit;
      res.message = deadline.reason() + " at t = " + std::to_string(static_cast<double>(k) * h);
      break;
    }
  }
  if (monitor) monitor->finish(res);
  res.contact_steps_min = contacts.shortest();
  res.contact_force_max = contacts.force_max();
  finish_steps(sys, tally, k, h, why, res);
  engine.finish(res);
  if (res.status != Status::ok) {
    res.pi1 = res.t_max = std::numeric_limits<double>::quiet_NaN();
  }
  return res;
}

StepOutcome dantzig_gave_up(std::string_view engine, long k, std::string_view unknowns, Result& res) {
  res.status = Status::failed;
  res.message = std::string(engine) + "'s Dantzig LCP gave up (degenerate pivot) at step " + std::to_string(k + 1) +
                ": the contact " + std::string(unknowns) + " of that step are wrong";
  return StepOutcome::taken_then_stop;
}

void finish_steps(const System& sys, const StepTally& tally, long k, double h, const char* why, Result& res) {
  res.steps = k;
  res.impacts = tally.impacts;
  if (tally.impacts > 0) note_impact(res, tally.first_impact, -tally.fastest_impact);
  res.contact_phases = tally.phases;
  res.min_gap = tally.g_min < 0.0 ? tally.g_min : std::numeric_limits<double>::infinity();
  if (res.status == Status::nan || res.status == Status::diverged) {
    std::ostringstream msg;
    if (!res.message.empty())
      msg << res.message;
    else
      msg << (why ? why : res.status == Status::nan ? "non-finite state" : "|u| above 1e6 a_p/w_p^2");
    msg << " at step " << k << " (t = " << static_cast<double>(k) * h
        << ", w_max h = " << 2.0 * std::numbers::pi * h / sys.t_min << ")";
    res.message = msg.str();
  }
  if (res.status != Status::ok) return;
  res.pi1 = sys.pi1(tally.u_max);
  res.t_max = static_cast<double>(tally.k_max) * h;
}

}  // namespace pb
