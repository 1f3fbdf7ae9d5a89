// The cvode integrator of the compliant solver (compliant.hpp): SUNDIALS CVODE over the
// state y = (u0, v0, u1, v1, ...) interleaved, so that a contact couples entries at most
// three apart and the Jacobian is banded (CVODE's band solver, its difference-quotient
// Jacobian). The run is cut at the pulse's end (the cosine pulse's load jumps there), at
// every breakpoint of any other load (a record's samples, where its slope jumps), and
// restarted (CVodeReInit) there and wherever a contact closes or opens.
//
// A yielding body (cases/README.md, "Yielding") is in one of three modes: elastic, its
// hysteretic variable z = u - p with a constant plastic offset p, or yielding outward at
// z = +u_y or -u_y. Within a mode its spring is linear, so the modes switch where CVODE finds
// their roots, as contacts do: u_y - |u - p| on the elastic branch (onset), the body's
// velocity on a yielding one (unloading, where p takes u -+ u_y so that z stays continuous),
// and the run restarts there. The ground's work, which the hysteretic share is measured
// against, is one more state W' = -sum m a_g v under the same error control; the energy the
// reference body's hysteresis dissipates, (1 - alpha) k u_y times its travel while yielding,
// is exact per phase.

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "solvers/compliant/compliant.hpp"
#include "solvers/compliant/cvode_objects.hpp"
#include "solvers/compliant/integrators.hpp"
#include "kit/contact_elements/elements.hpp"
#include "kit/fixed_step.hpp"
#include "kit/run_limits.hpp"

namespace pb::compliant {

namespace {

struct Problem {
  const System& sys;
  Elements& elements;
  LoadCursor load;  // a_g(t) of each evaluation: CVODE's times move back and forth by a step
  std::vector<double> u, v, f;  // scratch, one per body
  std::string library_message;  // the last error CVODE reported
  // Yielding (empty for an elastic system): per body its mode (0 elastic, +1 or -1 yielding
  // at z = +-u_y) and its plastic offset p (z = u - p on the elastic branch).
  std::vector<int> mode;
  std::vector<double> offset;
};

bool yielding(const Problem& pr) { return !pr.mode.empty(); }

// Body i's hysteretic variable at u (an elastic body's is u).
double hysteretic_z(const Problem& pr, std::size_t i, double u) {
  const Body& b = pr.sys.bodies[i];
  if (!yielding(pr) || !b.yields()) return u;
  return pr.mode[i] == 0 ? u - pr.offset[i] : pr.mode[i] * b.u_y;
}

// Body i's restoring force at u: k u for an elastic body, to the last bit as before.
double spring(const Problem& pr, std::size_t i, double u) {
  const Body& b = pr.sys.bodies[i];
  if (!yielding(pr) || !b.yields()) return b.k * u;
  return pr.sys.alpha * b.k * u + (1.0 - pr.sys.alpha) * b.k * hysteretic_z(pr, i, u);
}

void unpack(const double* y, std::vector<double>& u, std::vector<double>& v) {
  for (std::size_t i = 0; i < u.size(); ++i) {
    u[i] = y[2 * i];
    v[i] = y[2 * i + 1];
  }
}

int rhs(double t, N_Vector y, N_Vector ydot, void* data) {
  auto& pr = *static_cast<Problem*>(data);
  const double* yy = N_VGetArrayPointer(y);
  double* dy = N_VGetArrayPointer(ydot);
  unpack(yy, pr.u, pr.v);
  std::fill(pr.f.begin(), pr.f.end(), 0.0);
  pr.elements.add_forces(pr.u.data(), pr.v.data(), pr.f.data());
  const double ag = pr.load.accel(t);
  double power = 0.0;  // the ground's on every body
  for (std::size_t i = 0; i < pr.u.size(); ++i) {
    const Body& b = pr.sys.bodies[i];
    dy[2 * i] = pr.v[i];
    dy[2 * i + 1] = (pr.f[i] - spring(pr, i, pr.u[i]) - b.c * pr.v[i]) / b.m - ag;
    power -= b.m * ag * pr.v[i];
  }
  if (yielding(pr)) dy[2 * pr.u.size()] = power;
  return 0;
}

// Roots: every gap (the element starts and ends there) and body 0's velocity (the extremum
// of u0). Not the gap rates: two bodies that an element holds together move as one, their
// gap rate stays at zero, and CVODE stops on a root function that stays zero; the deepest
// penetration is read at the steps' ends instead.
int roots(double, N_Vector y, double* g, void* data) {
  auto& pr = *static_cast<Problem*>(data);
  unpack(N_VGetArrayPointer(y), pr.u, pr.v);
  const int nc = pr.sys.n_contacts();
  for (int j = 0; j < nc; ++j) g[j] = pr.sys.gap(j, pr.u.data());
  g[nc] = pr.v[ix(pr.sys.ref)];
  for (std::size_t i = 0; i < pr.mode.size(); ++i) {
    const Body& b = pr.sys.bodies[i];
    g[ix(nc) + 1 + i] = !b.yields()      ? 1.0
                        : pr.mode[i] == 0 ? b.u_y - std::abs(pr.u[i] - pr.offset[i])
                                          : pr.v[i];
  }
  return 0;
}

void keep_message(int, const char* module, const char* function, char* msg, void* data) {
  auto& pr = *static_cast<Problem*>(data);
  pr.library_message = std::string(module ? module : "") + "::" + (function ? function : "") + ": " + msg;
}

// One run: its SUNDIALS objects, the yielding modes, and what the steps measured.
class CvodeRun {
 public:
  CvodeRun(const System& sys, const Settings& set, Model model, double K)
      : sys_(sys),
        set_(set),
        n_(sys.n_bodies()),
        nc_(sys.n_contacts()),
        yields_(sys.yields()),
        neq_(static_cast<sunindextype>(2 * n_ + (yields_ ? 1 : 0))),  // + W with yielding
        rtol_(set.rtol > 0.0 ? set.rtol : kDefaultRtol),
        L_(sys.length_scale()),
        cap_(set.step_cap > 0 ? set.step_cap : kDefaultCvodeStepCap),
        n_roots_(nc_ + 1 + (yields_ ? n_ : 0)),
        elements_(sys, model, K),
        pr_{sys, elements_, LoadCursor(sys.pulse), start_u(sys), start_v(sys), std::vector<double>(ix(n_), 0.0), {},
            {}, {}},
        slack_(1e-10 * L_),
        v_slack_(slack_ * sys.pulse.w) {
    if (yields_) {
      pr_.mode.assign(ix(n_), 0);
      pr_.offset = pr_.u;  // every body starts at z = 0
    }
  }

  // CVODE made ready at the start state; what went wrong, else empty.
  std::string set_up(bool adams) {
    if (SUNContext_Create(nullptr, &cv_.context) != 0) return "SUNDIALS: no context";
    cv_.y = N_VNew_Serial(neq_, cv_.context);
    cv_.dky = N_VNew_Serial(neq_, cv_.context);
    N_Vector atol = N_VNew_Serial(neq_, cv_.context);
    y_ = N_VGetArrayPointer(cv_.y);
    start_state(N_VGetArrayPointer(atol));
    cv_.mem = CVodeCreate(adams ? CV_ADAMS : CV_BDF, cv_.context);
    CVodeSetErrHandlerFn(cv_.mem, keep_message, &pr_);  // a solver prints nothing
    int flag = CVodeInit(cv_.mem, rhs, 0.0, cv_.y);
    if (flag == CV_SUCCESS) flag = CVodeSVtolerances(cv_.mem, rtol_, atol);
    N_VDestroy(atol);
    if (flag == CV_SUCCESS) flag = CVodeSetUserData(cv_.mem, &pr_);
    cv_.band = SUNBandMatrix(neq_, 3, 3, cv_.context);
    cv_.linear = SUNLinSol_Band(cv_.y, cv_.band, cv_.context);
    if (flag == CV_SUCCESS) flag = CVodeSetLinearSolver(cv_.mem, cv_.linear, cv_.band);
    if (flag == CV_SUCCESS) flag = CVodeRootInit(cv_.mem, n_roots_, roots);
    if (flag == CV_SUCCESS) flag = CVodeSetNoInactiveRootWarn(cv_.mem);
    if (flag != CV_SUCCESS) return "CVODE set-up: " + flag_name(flag);
    return {};
  }

  // Steps to t_end, or until a status ends the run.
  Result integrate() {
    u_max_ = std::abs(pr_.u[ix(sys_.ref)]);
    found_.resize(ix(n_roots_));
    samples_ = static_cast<std::size_t>(std::max(set_.history_samples, 0));
    if (set_.history_samples > 0) {
      rows_ = &res_.history.data;
      res_.history.n_bodies = n_;
      res_.history.n_contacts = nc_;
    }
    deadline_.emplace(set_);
    const double t_pulse = std::min(sys_.pulse.duration(), sys_.t_end);
    stop_ = !sys_.pulse.paper() ? next_stop(0.0) : t_pulse > 0.0 ? t_pulse : sys_.t_end;
    CVodeSetStopTime(cv_.mem, stop_);
    while (t_ < sys_.t_end && step()) {
    }
    return finish();
  }

 private:
  // y and the absolute tolerances at t = 0.
  void start_state(double* at) {
    for (int i = 0; i < n_; ++i) {
      y_[2 * i] = pr_.u[ix(i)];
      y_[2 * i + 1] = pr_.v[ix(i)];
      // Lengths to rtol of a_p / w_p^2, velocities to rtol of a_p / w_p.
      at[2 * i] = rtol_ * L_;
      at[2 * i + 1] = rtol_ * L_ * sys_.pulse.w;
    }
    if (yields_) {
      y_[2 * n_] = 0.0;
      at[2 * n_] = rtol_ * sys_.energy_scale();
    }
  }

  // One CVODE step and what it changed; false where the run ends before t_end (its status set).
  bool step() {
    const int flag = CVode(cv_.mem, sys_.t_end, cv_.y, &t_, CV_ONE_STEP);
    if (flag < 0) {
      res_.status = Status::failed;
      res_.message = "CVODE: " + flag_name(flag) + " at t = " + std::to_string(t_) +
                     (pr_.library_message.empty() ? "" : " (" + pr_.library_message + ")");
      return false;
    }
    unpack(y_, pr_.u, pr_.v);
    bool finite = true;
    for (sunindextype i = 0; i < neq_; ++i) finite = finite && std::isfinite(y_[i]);
    if (!finite) {
      res_.status = Status::nan;
      why_ = "non-finite state";
      return false;
    }
    record_until(t_);
    track_extremes();
    if ((why_ = runaway(sys_, pr_.u.data(), pr_.v.data()))) {
      res_.status = Status::diverged;
      return false;
    }
    bool contacts_changed = flag == CV_ROOT_RETURN && take_roots();
    contacts_changed = reconcile(t_) || contacts_changed;
    contacts_changed = reconcile_yield() || contacts_changed;
    if (flag == CV_TSTOP_RETURN && t_ < sys_.t_end) {
      stop_ = sys_.pulse.paper() ? sys_.t_end : next_stop(t_);
      contacts_changed = true;  // the load may jump at the pulse's end
    }
    if (contacts_changed && t_ < sys_.t_end) restart(t_);
    return within_limits();
  }

  // The reference body's largest |u| and when, the deepest gap, the largest closed force.
  void track_extremes() {
    const double a = std::abs(pr_.u[ix(sys_.ref)]);
    if (a > u_max_) u_max_ = a, t_max_ = t_;
    for (int j = 0; j < nc_; ++j) {
      g_min_ = std::min(g_min_, sys_.gap(j, pr_.u.data()));
      if (elements_.closed(j)) f_max_ = std::max(f_max_, elements_.force(j, pr_.u.data(), pr_.v.data()));
    }
  }

  // The roots CVODE found at this step: contacts that close or open, modes that switch.
  // Whether anything changed (always, where a yielding root was found).
  bool take_roots() {
    bool changed = false;
    CVodeGetRootInfo(cv_.mem, found_.data());
    for (int j = 0; j < nc_; ++j) {
      if (found_[ix(j)] < 0) elements_.close(j, elements_.q(j, pr_.v.data()), t_), changed = true;
      if (found_[ix(j)] > 0) elements_.open(j, elements_.q(j, pr_.v.data())), changed = true;
    }
    // A root counts where the body crosses it outward (onset) or turns back (unloading): the
    // offset set at an unloading leaves |z| at u_y to an ulp, either side, and the elastic
    // root function can then cross zero at once as the body moves back in (measured: a run
    // of ten million steps, each such a root, before this test). The run restarts at every
    // such root, counted or not: its function can stay exactly zero over CVODE's next probe
    // (|u - p| moves below an ulp of u_y), which CVODE refuses (CV_ILL_INPUT, "root found at
    // and very near t") unless the root is a fresh start's, which it leaves inactive.
    for (int i = 0; i < n_ && yields_; ++i) {
      if (found_[ix(nc_ + 1 + i)] == 0 || !sys_.bodies[ix(i)].yields()) continue;
      const int m = pr_.mode[ix(i)];
      const double v = pr_.v[ix(i)];
      if (m == 0 && z_of(i) * v > 0.0) yield_onset(i);
      if (m != 0 && m * v <= 0.0) unload(i);
      changed = true;
    }
    return changed;
  }

  // The step cap and the time limit; false (the status set) where one has passed.
  bool within_limits() { return compliant::within_limits(total_steps(), cap_, *deadline_, t_, res_); }

  Result finish() {
    res_.steps = total_steps();
    res_.impacts = elements_.impacts();
    res_.min_gap = g_min_ < 0.0 ? g_min_ : std::numeric_limits<double>::infinity();
    res_.contact_force_max = f_max_;  // at CVODE's accepted steps: the force between them is not sampled
    elements_.finish(res_);
    if (res_.status == Status::nan || res_.status == Status::diverged)
      res_.message = std::string(why_) + " at t = " + std::to_string(t_);
    if (res_.status == Status::ok) {
      res_.pi1 = sys_.pi1(u_max_);
      res_.t_max = t_max_;
      if (yields_) {
        const int r = sys_.ref;
        if (sys_.bodies[ix(r)].yields() && pr_.mode[ix(r)] != 0) dissipated_ += phase_work(r);
        res_.residual = sys_.residual(pr_.u[ix(r)], z_of(r));
        res_.hysteretic = dissipated_ / y_[2 * n_];
      }
    }
    return std::move(res_);
  }

  double sample_time(std::size_t s) const {
    return samples_ > 1 ? sys_.t_end * static_cast<double>(s) / static_cast<double>(samples_ - 1) : 0.0;
  }

  // History rows up to t from CVODE's interpolant (valid back to the last step's start).
  void record_until(double t) {
    while (rows_ && next_sample_ < samples_ && sample_time(next_sample_) <= t) {
      const double ts = sample_time(next_sample_++);
      CVodeGetDky(cv_.mem, ts, 0, cv_.dky);
      const double* d = N_VGetArrayPointer(cv_.dky);
      std::vector<double> u(ix(n_)), v(ix(n_));
      unpack(d, u, v);
      rows_->push_back(ts);
      rows_->insert(rows_->end(), u.begin(), u.end());
      rows_->insert(rows_->end(), v.begin(), v.end());
      for (int j = 0; j < nc_; ++j) rows_->push_back(sys_.gap(j, u.data()));
      for (int j = 0; j < nc_; ++j) rows_->push_back(elements_.force(j, u.data(), v.data()));
    }
  }

  // A contact whose state disagrees with its gap by more than round-off (one that closed
  // at t = 0 with Pi3 = 0, where CVODE ignores a root function that starts at zero).
  bool reconcile(double t) {
    bool changed = false;
    for (int j = 0; j < nc_; ++j) {
      const double g = sys_.gap(j, pr_.u.data());
      if (!elements_.closed(j) && g < -slack_) elements_.close(j, elements_.q(j, pr_.v.data()), t), changed = true;
      if (elements_.closed(j) && g > slack_) elements_.open(j, elements_.q(j, pr_.v.data())), changed = true;
    }
    return changed;
  }

  // Yielding: the modes' switches, and the energy the reference body's hysteresis dissipated
  // over its finished yielding phases (u_onset_: where its current one began).
  double z_of(int i) const { return hysteretic_z(pr_, ix(i), pr_.u[ix(i)]); }
  double phase_work(int i) const {
    const Body& b = sys_.bodies[ix(i)];
    return (1.0 - sys_.alpha) * b.k * b.u_y * pr_.mode[ix(i)] * (pr_.u[ix(i)] - u_onset_);
  }
  void yield_onset(int i) {
    pr_.mode[ix(i)] = z_of(i) > 0.0 ? 1 : -1;
    if (i == sys_.ref) u_onset_ = pr_.u[ix(i)];
  }
  void unload(int i) {
    if (i == sys_.ref) dissipated_ += phase_work(i);
    pr_.offset[ix(i)] = pr_.u[ix(i)] - pr_.mode[ix(i)] * sys_.bodies[ix(i)].u_y;
    pr_.mode[ix(i)] = 0;
  }
  // A mode its state contradicts by more than round-off: a root CVODE ignored because its
  // function started at zero (a yield reached at a velocity's zero, whose yielding branch's
  // root function, the velocity, starts there).
  bool reconcile_yield() {
    bool changed = false;
    for (int i = 0; i < n_ && yields_; ++i) {
      const Body& b = sys_.bodies[ix(i)];
      if (!b.yields()) continue;
      const int m = pr_.mode[ix(i)];
      if (m == 0 && std::abs(z_of(i)) > b.u_y + slack_) yield_onset(i), changed = true;
      if (m != 0 && m * pr_.v[ix(i)] < -v_slack_) unload(i), changed = true;
    }
    return changed;
  }

  long total_steps() const {
    long nst = 0;
    CVodeGetNumSteps(cv_.mem, &nst);
    return done_ + nst;
  }
  // Any other load than the paper's pulses is cut at each of its breakpoints (a record's
  // samples, where its slope jumps; a pulse model's end), so that no step straddles one.
  double next_stop(double from) const { return std::min(sys_.pulse.next_break(from), sys_.t_end); }
  void restart(double at_t) {
    done_ = total_steps();
    CVodeReInit(cv_.mem, at_t, cv_.y);
    CVodeSetStopTime(cv_.mem, stop_);
  }

  const System& sys_;
  const Settings& set_;
  const int n_, nc_;
  const bool yields_;
  const sunindextype neq_;
  const double rtol_, L_;
  const long cap_;
  const int n_roots_;
  Elements elements_;
  Problem pr_;
  Cvode cv_;
  double* y_ = nullptr;  // cv_.y's entries
  Result res_;
  double u_max_ = 0.0, t_max_ = 0.0, g_min_ = 0.0, f_max_ = 0.0;
  std::vector<int> found_;
  std::vector<double>* rows_ = nullptr;  // the history's, when it is recorded
  std::size_t next_sample_ = 0, samples_ = 0;
  const double slack_, v_slack_;
  double dissipated_ = 0.0, u_onset_ = 0.0;
  std::optional<Deadline> deadline_;  // its clock started after the set-up, as the steps start
  long done_ = 0;  // the steps of the segments before the last restart
  double t_ = 0.0, stop_ = 0.0;
  const char* why_ = nullptr;
};

}  // namespace

Result run_cvode(const System& sys, const Settings& set, Model model, double K, bool adams) {
  CvodeRun run(sys, set, model, K);
  if (const std::string why = run.set_up(adams); !why.empty()) return failed(why);
  return run.integrate();
}

}  // namespace pb::compliant
