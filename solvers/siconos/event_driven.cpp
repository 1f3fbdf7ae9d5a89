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

// The run's events after its set-up: each one's state, impulses and peaks, to the end.
class EventLoop {
 public:
  EventLoop(const System& sys, const Settings& set, engine::EventDrivenRun& run, Deadline& deadline)
      : sys_(sys),
        set_(set),
        run_(run),
        deadline_(deadline),
        units_(units_of(sys)),
        force_unit_(units_.length / (units_.time * units_.time)),  // per unit mass
        nc_(sys.n_contacts()),
        ref_(static_cast<std::size_t>(sys.ref)),
        floor_(kRestitutionFloor * sys.a_p / sys.pulse.w),
        cap_(set.step_cap > 0 ? set.step_cap : kDefaultEventCap),
        recording_(set.history_samples > 0),
        st_(sys),
        before_(sys) {}

  Result run() {
    start();
    while (run_.has_next() && next()) {
    }
    return finish();
  }

 private:
  // The state at t = 0, and the history's first row.
  void start() {
    st_.read(run_, sys_, units_);
    force_.resize(st_.g.size());
    closed_.resize(st_.g.size());
    t_.peak({std::abs(st_.u[ref_]), 0.0});
    for (double g : st_.g) t_.g_min = std::min(t_.g_min, g);
    if (recording_) {
      res_.history.n_bodies = sys_.n_bodies();
      res_.history.n_contacts = nc_;
      // A row per event: the output points, and the roots on top of them (rarely many).
      const auto rows = static_cast<std::size_t>(step_count(sys_.t_end, output_step(sys_)) + 1);
      res_.history.data.reserve(2 * rows * static_cast<std::size_t>(res_.history.row_size()));
      record(0.0, st_, force_, res_.history.data);
    }
  }

  // One event of Siconos' and what it did; false where the run ends early (its status set).
  bool next() {
    if (events_ >= cap_) {
      res_.status = Status::step_cap;
      res_.message = "more than " + std::to_string(cap_) + " events";
      return false;
    }
    const double u_last = st_.u[ref_], v_last = st_.v[ref_];
    if (!advance()) return false;
    ++events_;
    st_.read(run_, sys_, units_);
    const double now = run_.time() * units_.time;
    res_.status = state_end(sys_, before_.finite() && st_.finite(), st_.u.data(), st_.v.data(), now, res_.message);
    if (res_.status != Status::ok) return false;
    // Between two events the motion is smooth: its largest |u0| is that of the cubic through
    // the state after the last event and the state before this one.
    t_.peak(hermite_peak(t_last_, now - t_last_, u_last, v_last, before_.u[ref_], before_.v[ref_]));
    t_.peak({std::abs(before_.u[ref_]), now});
    t_.peak({std::abs(st_.u[ref_]), now});
    take_impulses(now);
    if (recording_) record(now, st_, force_, res_.history.data);
    t_last_ = now;
    if (deadline_.tick()) {
      res_.status = Status::time_limit;
      res_.message = deadline_.reason() + " at t = " + std::to_string(now);
      return false;
    }
    return true;
  }

  // Siconos to its next event, the state before it read; false (the status set) where it
  // stopped or failed.
  bool advance() {
    try {
      if (run_.advance()) ++t_.roots;
      before_.read(run_, sys_, units_);
      run_.process();
    } catch (const engine::Stopped&) {
      res_.status = Status::time_limit;
      res_.message = deadline_.reason() + " at t = " + std::to_string(t_last_);
      return false;
    } catch (const std::exception& e) {
      res_.status = Status::failed;
      res_.message = std::string("Siconos: ") + e.what() + " (after " + std::to_string(events_) + " events, t = " +
                     std::to_string(t_last_) + ")";
      return false;
    }
    return true;
  }

  // The impulses of this event (none at an output point), and what they did.
  void take_impulses(double now) {
    int pushed = 0, last = 0;
    for (int j = 0; j < nc_; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      if (run_.impulse(j) > 0.0) {
        ++pushed;
        last = j;
        if (before_.rate[jj] < 0.0) {
          ++t_.impacts;
          note_impact(res_, now, before_.rate[jj]);
        }
      }
      const bool now_closed = run_.closed(j);
      if (now_closed && !closed_[jj]) ++t_.phases;
      closed_[jj] = now_closed ? 1 : 0;
      force_[jj] = run_.force(j) * force_unit_;
      t_.g_min = std::min({t_.g_min, st_.g[jj], before_.g[jj]});
    }
    const auto l = static_cast<std::size_t>(last);
    if (set_.monitor && pushed == 1 && before_.rate[l] < -floor_) t_.restitution(-st_.rate[l] / before_.rate[l]);
  }

  Result finish() {
    res_.steps = events_;
    res_.impacts = t_.impacts;
    res_.contact_phases = t_.phases;
    res_.min_gap = t_.g_min < 0.0 ? t_.g_min : std::numeric_limits<double>::infinity();
    res_.isolated_impacts = t_.isolated;
    res_.restitution_low = t_.e_low;
    res_.restitution_high = t_.e_high;
    if (res_.status != Status::ok) return std::move(res_);
    std::ostringstream msg;
    msg << "lsodar: " << run_.lsodar_steps() << " steps, " << run_.lsodar_rhs_calls() << " rhs calls; events: "
        << events_ - t_.roots << " output points, " << t_.roots << " roots";
    res_.message = msg.str();
    res_.pi1 = sys_.pi1(t_.u_max.value);
    res_.t_max = t_.u_max.at;
    return std::move(res_);
  }

  const System& sys_;
  const Settings& set_;
  engine::EventDrivenRun& run_;
  Deadline& deadline_;
  const Units units_;
  const double force_unit_;
  const int nc_;
  const std::size_t ref_;
  const double floor_;
  const long cap_;
  const bool recording_;
  Result res_;
  State st_, before_;
  std::vector<double> force_;
  std::vector<char> closed_;
  Tally t_;
  double t_last_ = 0.0;
  long events_ = 0;
};

}  // namespace

Result run_event_driven(const System& sys, const Settings& set) {
  if (std::string bad = check_system(sys); !bad.empty()) return stopped(Status::failed, bad);
  if (!(sys.t_end / output_step(sys) < 1e9)) return stopped(Status::failed, "t_end: more than 1e9 output points");
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
  return EventLoop(sys, set, run, deadline).run();
}

EventDrivenSetup event_driven_setup(const System& system, const Settings& settings) {
  const auto run = make_run(system, settings, nullptr);
  return {run->itol(), run->rtol(), run->atol(), run->event_tolerance(), run->itask()};
}

}  // namespace pb::siconos
