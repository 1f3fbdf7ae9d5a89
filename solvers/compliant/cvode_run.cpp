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
#include <string>
#include <vector>

#include "solvers/compliant/compliant.hpp"
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

std::string flag_name(int flag) {
  char* text = CVodeGetReturnFlagName(flag);
  std::string out = text ? text : std::to_string(flag);
  std::free(text);
  return out;
}

// The SUNDIALS objects of one run, released in order whatever happens.
struct Cvode {
  SUNContext context = nullptr;
  N_Vector y = nullptr, dky = nullptr;
  SUNMatrix band = nullptr;
  SUNLinearSolver linear = nullptr;
  void* mem = nullptr;
  ~Cvode() {
    if (mem) CVodeFree(&mem);
    if (linear) SUNLinSolFree(linear);
    if (band) SUNMatDestroy(band);
    if (dky) N_VDestroy(dky);
    if (y) N_VDestroy(y);
    if (context) SUNContext_Free(&context);
  }
};

}  // namespace

Result run_cvode(const System& sys, const Settings& set, Model model, double K, bool adams) {
  const int n = sys.n_bodies(), nc = sys.n_contacts();
  const bool yields = sys.yields();
  const auto neq = static_cast<sunindextype>(2 * n + (yields ? 1 : 0));  // + W with yielding
  const double rtol = set.rtol > 0.0 ? set.rtol : kDefaultRtol;
  const double L = sys.length_scale();
  const long cap = set.step_cap > 0 ? set.step_cap : kDefaultCvodeStepCap;

  Elements elements(sys, model, K);
  Problem pr{sys, elements, LoadCursor(sys.pulse), start_u(sys), start_v(sys), std::vector<double>(ix(n), 0.0), {},
             {}, {}};
  if (yields) {
    pr.mode.assign(ix(n), 0);
    pr.offset = pr.u;  // every body starts at z = 0
  }
  Cvode cv;
  if (SUNContext_Create(nullptr, &cv.context) != 0) return failed("SUNDIALS: no context");
  cv.y = N_VNew_Serial(neq, cv.context);
  cv.dky = N_VNew_Serial(neq, cv.context);
  N_Vector atol = N_VNew_Serial(neq, cv.context);
  double* y = N_VGetArrayPointer(cv.y);
  double* at = N_VGetArrayPointer(atol);
  for (int i = 0; i < n; ++i) {
    y[2 * i] = pr.u[ix(i)];
    y[2 * i + 1] = pr.v[ix(i)];
    // Lengths to rtol of a_p / w_p^2, velocities to rtol of a_p / w_p.
    at[2 * i] = rtol * L;
    at[2 * i + 1] = rtol * L * sys.pulse.w;
  }
  if (yields) {
    y[2 * n] = 0.0;
    at[2 * n] = rtol * sys.energy_scale();
  }
  cv.mem = CVodeCreate(adams ? CV_ADAMS : CV_BDF, cv.context);
  CVodeSetErrHandlerFn(cv.mem, keep_message, &pr);  // a solver prints nothing
  int flag = CVodeInit(cv.mem, rhs, 0.0, cv.y);
  if (flag == CV_SUCCESS) flag = CVodeSVtolerances(cv.mem, rtol, atol);
  N_VDestroy(atol);
  if (flag == CV_SUCCESS) flag = CVodeSetUserData(cv.mem, &pr);
  cv.band = SUNBandMatrix(neq, 3, 3, cv.context);
  cv.linear = SUNLinSol_Band(cv.y, cv.band, cv.context);
  if (flag == CV_SUCCESS) flag = CVodeSetLinearSolver(cv.mem, cv.linear, cv.band);
  const int n_roots = nc + 1 + (yields ? n : 0);
  if (flag == CV_SUCCESS) flag = CVodeRootInit(cv.mem, n_roots, roots);
  if (flag == CV_SUCCESS) flag = CVodeSetNoInactiveRootWarn(cv.mem);
  if (flag != CV_SUCCESS) return failed("CVODE set-up: " + flag_name(flag));

  Result res;
  double u_max = std::abs(pr.u[ix(sys.ref)]), t_max = 0.0, g_min = 0.0, f_max = 0.0;
  std::vector<int> found(ix(n_roots));
  std::vector<double>* rows = set.history_samples > 0 ? &res.history.data : nullptr;
  std::size_t next_sample = 0;
  const std::size_t samples = static_cast<std::size_t>(std::max(set.history_samples, 0));
  if (rows) {
    res.history.n_bodies = n;
    res.history.n_contacts = nc;
  }
  const auto sample_time = [&](std::size_t s) {
    return samples > 1 ? sys.t_end * static_cast<double>(s) / static_cast<double>(samples - 1) : 0.0;
  };
  // History rows up to t from CVODE's interpolant (valid back to the last step's start).
  const auto record_until = [&](double t) {
    while (rows && next_sample < samples && sample_time(next_sample) <= t) {
      const double ts = sample_time(next_sample++);
      CVodeGetDky(cv.mem, ts, 0, cv.dky);
      const double* d = N_VGetArrayPointer(cv.dky);
      std::vector<double> u(ix(n)), v(ix(n));
      unpack(d, u, v);
      rows->push_back(ts);
      rows->insert(rows->end(), u.begin(), u.end());
      rows->insert(rows->end(), v.begin(), v.end());
      for (int j = 0; j < nc; ++j) rows->push_back(sys.gap(j, u.data()));
      for (int j = 0; j < nc; ++j) rows->push_back(elements.force(j, u.data(), v.data()));
    }
  };
  // A contact whose state disagrees with its gap by more than round-off (one that closed
  // at t = 0 with Pi3 = 0, where CVODE ignores a root function that starts at zero).
  const double slack = 1e-10 * L;
  const auto reconcile = [&](double t) {
    bool changed = false;
    for (int j = 0; j < nc; ++j) {
      const double g = sys.gap(j, pr.u.data());
      if (!elements.closed(j) && g < -slack) elements.close(j, elements.q(j, pr.v.data()), t), changed = true;
      if (elements.closed(j) && g > slack) elements.open(j, elements.q(j, pr.v.data())), changed = true;
    }
    return changed;
  };

  // Yielding: the modes' switches, and the energy the reference body's hysteresis dissipated
  // over its finished yielding phases (u_onset: where its current one began).
  double dissipated = 0.0, u_onset = 0.0;
  const auto z_of = [&](int i) { return hysteretic_z(pr, ix(i), pr.u[ix(i)]); };
  const auto phase_work = [&](int i) {
    const Body& b = sys.bodies[ix(i)];
    return (1.0 - sys.alpha) * b.k * b.u_y * pr.mode[ix(i)] * (pr.u[ix(i)] - u_onset);
  };
  const auto yield_onset = [&](int i) {
    pr.mode[ix(i)] = z_of(i) > 0.0 ? 1 : -1;
    if (i == sys.ref) u_onset = pr.u[ix(i)];
  };
  const auto unload = [&](int i) {
    if (i == sys.ref) dissipated += phase_work(i);
    pr.offset[ix(i)] = pr.u[ix(i)] - pr.mode[ix(i)] * sys.bodies[ix(i)].u_y;
    pr.mode[ix(i)] = 0;
  };
  // A mode its state contradicts by more than round-off: a root CVODE ignored because its
  // function started at zero (a yield reached at a velocity's zero, whose yielding branch's
  // root function, the velocity, starts there).
  const double v_slack = slack * sys.pulse.w;
  const auto reconcile_yield = [&]() {
    bool changed = false;
    for (int i = 0; i < n && yields; ++i) {
      const Body& b = sys.bodies[ix(i)];
      if (!b.yields()) continue;
      const int m = pr.mode[ix(i)];
      if (m == 0 && std::abs(z_of(i)) > b.u_y + slack) yield_onset(i), changed = true;
      if (m != 0 && m * pr.v[ix(i)] < -v_slack) unload(i), changed = true;
    }
    return changed;
  };

  Deadline deadline(set);
  long done = 0;  // the steps of the segments before the last restart
  const auto total_steps = [&]() {
    long nst = 0;
    CVodeGetNumSteps(cv.mem, &nst);
    return done + nst;
  };
  double t = 0.0;
  const double t_pulse = std::min(sys.pulse.duration(), sys.t_end);
  // Any other load than the paper's pulses is cut at each of its breakpoints (a record's
  // samples, where its slope jumps; a pulse model's end), so that no step straddles one.
  const auto next_stop = [&](double from) { return std::min(sys.pulse.next_break(from), sys.t_end); };
  double stop = !sys.pulse.paper() ? next_stop(0.0) : t_pulse > 0.0 ? t_pulse : sys.t_end;
  CVodeSetStopTime(cv.mem, stop);
  const auto restart = [&](double at_t) {
    done = total_steps();
    CVodeReInit(cv.mem, at_t, cv.y);
    CVodeSetStopTime(cv.mem, stop);
  };
  const char* why = nullptr;
  while (t < sys.t_end) {
    flag = CVode(cv.mem, sys.t_end, cv.y, &t, CV_ONE_STEP);
    if (flag < 0) {
      res.status = Status::failed;
      res.message = "CVODE: " + flag_name(flag) + " at t = " + std::to_string(t) +
                    (pr.library_message.empty() ? "" : " (" + pr.library_message + ")");
      break;
    }
    unpack(y, pr.u, pr.v);
    bool finite = true;
    for (sunindextype i = 0; i < neq; ++i) finite = finite && std::isfinite(y[i]);
    if (!finite) {
      res.status = Status::nan;
      why = "non-finite state";
      break;
    }
    record_until(t);
    const double a = std::abs(pr.u[ix(sys.ref)]);
    if (a > u_max) u_max = a, t_max = t;
    for (int j = 0; j < nc; ++j) {
      g_min = std::min(g_min, sys.gap(j, pr.u.data()));
      if (elements.closed(j)) f_max = std::max(f_max, elements.force(j, pr.u.data(), pr.v.data()));
    }
    if ((why = runaway(sys, pr.u.data(), pr.v.data()))) {
      res.status = Status::diverged;
      break;
    }
    bool contacts_changed = false;
    if (flag == CV_ROOT_RETURN) {
      CVodeGetRootInfo(cv.mem, found.data());
      for (int j = 0; j < nc; ++j) {
        if (found[ix(j)] < 0) elements.close(j, elements.q(j, pr.v.data()), t), contacts_changed = true;
        if (found[ix(j)] > 0) elements.open(j, elements.q(j, pr.v.data())), contacts_changed = true;
      }
      // A root counts where the body crosses it outward (onset) or turns back (unloading): the
      // offset set at an unloading leaves |z| at u_y to an ulp, either side, and the elastic
      // root function can then cross zero at once as the body moves back in (measured: a run
      // of ten million steps, each such a root, before this test). The run restarts at every
      // such root, counted or not: its function can stay exactly zero over CVODE's next probe
      // (|u - p| moves below an ulp of u_y), which CVODE refuses (CV_ILL_INPUT, "root found at
      // and very near t") unless the root is a fresh start's, which it leaves inactive.
      for (int i = 0; i < n && yields; ++i) {
        if (found[ix(nc + 1 + i)] == 0 || !sys.bodies[ix(i)].yields()) continue;
        const int m = pr.mode[ix(i)];
        const double v = pr.v[ix(i)];
        if (m == 0 && z_of(i) * v > 0.0) yield_onset(i);
        if (m != 0 && m * v <= 0.0) unload(i);
        contacts_changed = true;
      }
    }
    contacts_changed = reconcile(t) || contacts_changed;
    contacts_changed = reconcile_yield() || contacts_changed;
    if (flag == CV_TSTOP_RETURN && t < sys.t_end) {
      stop = sys.pulse.paper() ? sys.t_end : next_stop(t);
      contacts_changed = true;  // the load may jump at the pulse's end
    }
    if (contacts_changed && t < sys.t_end) restart(t);
    const long steps = total_steps();
    if (steps > cap) {
      res.status = Status::step_cap;
      res.message = "more than " + std::to_string(cap) + " CVODE steps";
      break;
    }
    if (deadline.passed(steps)) {
      res.status = Status::time_limit;
      res.message = deadline.reason() + " at t = " + std::to_string(t);
      break;
    }
  }
  res.steps = total_steps();
  res.impacts = elements.impacts();
  res.min_gap = g_min < 0.0 ? g_min : std::numeric_limits<double>::infinity();
  res.contact_force_max = f_max;  // at CVODE's accepted steps: the force between them is not sampled
  elements.finish(res);
  if (res.status == Status::nan || res.status == Status::diverged)
    res.message = std::string(why) + " at t = " + std::to_string(t);
  if (res.status == Status::ok) {
    res.pi1 = sys.pi1(u_max);
    res.t_max = t_max;
    if (yields) {
      const int r = sys.ref;
      if (sys.bodies[ix(r)].yields() && pr.mode[ix(r)] != 0) dissipated += phase_work(r);
      res.residual = sys.residual(pr.u[ix(r)], z_of(r));
      res.hysteretic = dissipated / y[2 * n];
    }
  }
  return res;
}

}  // namespace pb::compliant
