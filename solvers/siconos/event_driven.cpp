// The event-driven variant: Siconos' EventDriven simulation with LsodarOSI. LSODAR integrates
// the smooth motion (with the acceleration-level LCP of the closed contacts in its right-hand
// side) and stops where a gap closes, a root of its g functions; there Siconos applies
// Newton's impact law through its impact LCP. The run also stops at every point of an output
// grid of T_min / kOutputSteps, where this code sees the state.

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "kit/fixed_step.hpp"
#include "kit/monitor.hpp"
#include "kit/run_limits.hpp"
#include "solvers/siconos/model.hpp"

namespace pb::siconos {

namespace {

double output_step(const System& sys) { return sys.t_min / kOutputSteps; }

// A run whose load plugin ticks `deadline` (may be null: none).
std::unique_ptr<engine::EventDrivenRun> make_run(const System& sys, const Settings& set, Deadline* deadline) {
  const double h = output_step(sys);
  // Siconos' horizon half a step past the last output point at or after t_end.
  const double horizon = (static_cast<double>(step_count(sys.t_end, h)) + 0.5) * h;
  engine::ModelSpec spec = model_spec(sys, h, horizon);
  if (deadline) {
    spec.stop = &deadline_passed;
    spec.stop_data = deadline;
  }
  return std::make_unique<engine::EventDrivenRun>(spec, h / units_of(sys).time, kRtol * set.tol_scale,
                                                  kAtol * set.tol_scale);
}

// The largest |p| at the interior extrema of the cubic Hermite interpolant p on [t0, t0 + H]
// with p(t0) = u0, p'(t0) = v0, p(t0 + H) = u1, p'(t0 + H) = v1, and where it is ({0, t0} if
// p has no interior extremum).
struct Peak {
  double value = 0.0, at = 0.0;
};
Peak hermite_peak(double t0, double H, double u0, double v0, double u1, double v1) {
  // p = u0 + v0 H x + a x^2 + b x^3 with x = (t - t0) / H; p' = 0 where 3 b x^2 + 2 a x + v0 H = 0.
  const double d = u1 - u0, a = 3.0 * d - (2.0 * v0 + v1) * H, b = -2.0 * d + (v0 + v1) * H;
  Peak peak{0.0, t0};
  const auto consider = [&](double x) {
    const double p = std::abs(u0 + x * (v0 * H + x * (a + x * b)));
    if (x > 0.0 && x < 1.0 && p > peak.value) peak = {p, t0 + x * H};
  };
  const double qa = 3.0 * b, qb = 2.0 * a, qc = v0 * H;
  if (qa == 0.0) {
    if (qb != 0.0) consider(-qc / qb);
    return peak;
  }
  const double disc = qb * qb - 4.0 * qa * qc;
  if (disc < 0.0) return peak;
  const double r = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));  // the roots without cancellation
  if (r != 0.0) {
    consider(r / qa);
    consider(qc / r);
  }
  return peak;
}

struct Tally {
  Peak u_max;
  double g_min = 0.0;
  long impacts = 0, phases = 0, roots = 0, isolated = 0;
  double e_low = std::numeric_limits<double>::quiet_NaN(), e_high = e_low;

  void peak(const Peak& p) {
    if (p.value > u_max.value) u_max = p;
  }
  void restitution(double e) {
    ++isolated;
    e_low = isolated == 1 ? e : std::min(e_low, e);
    e_high = isolated == 1 ? e : std::max(e_high, e);
  }
};

}  // namespace

Result run_event_driven(const System& sys, const Settings& set) {
  if (std::string bad = check_system(sys); !bad.empty()) return stopped(Status::failed, bad);
  if (!(sys.t_end / output_step(sys) < 1e9)) return stopped(Status::failed, "t_end: more than 1e9 output points");
  const long cap = set.step_cap > 0 ? set.step_cap : kDefaultEventCap;
  // The limit holds from here, through Siconos' set-up: LsodarOSI sizes its work arrays anew
  // for each body it is given, (2i)^2 doubles for the i-th, zeroed: O(n^3), 8.3 s for a chain
  // of 1000 bodies, 0.54 s for 400. The load plugin ticks the deadline once per body there
  // and in every right-hand side LSODAR evaluates (engine::ModelSpec::stop).
  Deadline deadline(set);
  std::unique_ptr<engine::EventDrivenRun> made;
  try {
    made = make_run(sys, set, &deadline);
  } catch (const engine::Stopped&) {
    return stopped(Status::time_limit, deadline.reason() + " in Siconos' set-up of " +
                                           std::to_string(sys.n_bodies()) + " bodies");
  }
  engine::EventDrivenRun& run = *made;
  if (run.itol() != 1 || run.rtol() != kRtol * set.tol_scale || run.atol() != kAtol * set.tol_scale)
    return stopped(Status::failed, "LsodarOSI does not hold the tolerances set");

  const Units units = units_of(sys);
  const double force_unit = units.length / (units.time * units.time);  // per unit mass
  const int nc = sys.n_contacts();
  const auto ref = static_cast<std::size_t>(sys.ref);
  const double floor = kRestitutionFloor * sys.a_p / sys.pulse.w;
  Result res;
  State st(sys), before(sys);
  st.read(run, sys, units);
  std::vector<double> force(st.g.size());
  std::vector<char> closed(st.g.size());
  Tally t;
  t.peak({std::abs(st.u[ref]), 0.0});
  for (double g : st.g) t.g_min = std::min(t.g_min, g);
  const bool recording = set.history_samples > 0;
  if (recording) {
    res.history.n_bodies = sys.n_bodies();
    res.history.n_contacts = nc;
    // A row per event: the output points, and the roots on top of them (rarely many).
    const auto rows = static_cast<std::size_t>(step_count(sys.t_end, output_step(sys)) + 1);
    res.history.data.reserve(2 * rows * static_cast<std::size_t>(res.history.row_size()));
    record(0.0, st, force, res.history.data);
  }
  double t_last = 0.0;
  long events = 0;
  while (run.has_next()) {
    if (events >= cap) {
      res.status = Status::step_cap;
      res.message = "more than " + std::to_string(cap) + " events";
      break;
    }
    const double u_last = st.u[ref], v_last = st.v[ref];
    try {
      if (run.advance()) ++t.roots;
      before.read(run, sys, units);
      run.process();
    } catch (const engine::Stopped&) {
      res.status = Status::time_limit;
      res.message = deadline.reason() + " at t = " + std::to_string(t_last);
      break;
    } catch (const std::exception& e) {
      res.status = Status::failed;
      res.message = std::string("Siconos: ") + e.what() + " (after " + std::to_string(events) + " events, t = " +
                    std::to_string(t_last) + ")";
      break;
    }
    ++events;
    st.read(run, sys, units);
    const double now = run.time() * units.time;
    res.status = state_end(sys, before.finite() && st.finite(), st.u.data(), st.v.data(), now, res.message);
    if (res.status != Status::ok) break;
    // Between two events the motion is smooth: its largest |u0| is that of the cubic through
    // the state after the last event and the state before this one.
    t.peak(hermite_peak(t_last, now - t_last, u_last, v_last, before.u[ref], before.v[ref]));
    t.peak({std::abs(before.u[ref]), now});
    t.peak({std::abs(st.u[ref]), now});
    // The impulses of this event (none at an output point), and what they did.
    int pushed = 0, last = 0;
    for (int j = 0; j < nc; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      if (run.impulse(j) > 0.0) {
        ++pushed;
        last = j;
        if (before.rate[jj] < 0.0) {
          ++t.impacts;
          note_impact(res, now, before.rate[jj]);
        }
      }
      const bool now_closed = run.closed(j);
      if (now_closed && !closed[jj]) ++t.phases;
      closed[jj] = now_closed ? 1 : 0;
      force[jj] = run.force(j) * force_unit;
      t.g_min = std::min({t.g_min, st.g[jj], before.g[jj]});
    }
    const auto l = static_cast<std::size_t>(last);
    if (set.monitor && pushed == 1 && before.rate[l] < -floor) t.restitution(-st.rate[l] / before.rate[l]);
    if (recording) record(now, st, force, res.history.data);
    t_last = now;
    if (deadline.tick()) {
      res.status = Status::time_limit;
      res.message = deadline.reason() + " at t = " + std::to_string(now);
      break;
    }
  }
  res.steps = events;
  res.impacts = t.impacts;
  res.contact_phases = t.phases;
  res.min_gap = t.g_min < 0.0 ? t.g_min : std::numeric_limits<double>::infinity();
  res.isolated_impacts = t.isolated;
  res.restitution_low = t.e_low;
  res.restitution_high = t.e_high;
  if (res.status != Status::ok) return res;
  std::ostringstream msg;
  msg << "lsodar: " << run.lsodar_steps() << " steps, " << run.lsodar_rhs_calls() << " rhs calls; events: "
      << events - t.roots << " output points, " << t.roots << " roots";
  res.message = msg.str();
  res.pi1 = sys.pi1(t.u_max.value);
  res.t_max = t.u_max.at;
  return res;
}

EventDrivenSetup event_driven_setup(const System& system, const Settings& settings) {
  const auto run = make_run(system, settings, nullptr);
  return {run->itol(), run->rtol(), run->atol(), run->event_tolerance(), run->itask()};
}

}  // namespace pb::siconos
