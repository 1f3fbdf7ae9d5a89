// The compliant solver's cvode integrator on the buildings scene (buildings.hpp): SUNDIALS
// CVODE over y = (u, v) of each floor interleaved, the floors level by level (floors.hpp), so
// that the Jacobian is banded with the bandwidth of the storeys and contacts (CVODE's band
// solver and its difference-quotient Jacobian, as on the single oscillators). Its objects and
// vectors are made once per run; a step allocates nothing.
//
// Root functions: every gap (an element starts and ends there, and CVODE restarts: a
// Kelvin-Voigt force jumps by c q at onset), every floor's velocity and every upper storey's
// drift rate (a storey on the ground drifts as its floor moves): each floor's and storey's
// peak is at a root of its rate or at a run's end, so the peaks are read at those roots (and at
// every step's end), not between steps. Not the gap rates: two floors an element holds together
// have a gap rate that stays at zero, which CVODE refuses as a root function; the deepest
// penetration is read at the returns. The run is cut at the pulse's end (the cosine pulse's
// load jumps there) and at every breakpoint of any other load, as on the single oscillators
// (cvode_run.cpp), and restarted there.

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "kit/fixed_step.hpp"
#include "kit/run_limits.hpp"
#include "solvers/compliant/buildings.hpp"
#include "solvers/compliant/compliant.hpp"
#include "solvers/compliant/cvode_objects.hpp"
#include "solvers/compliant/floors.hpp"

namespace pb::compliant::building_cvode {

namespace {

struct Problem {
  const Floors& floors;
  LoadCursor load;  // a_g(t) of each evaluation: CVODE's times move back and forth by a step
  std::vector<double> u, v, f;  // scratch, in global floor order
  std::vector<int> upper;       // the floors whose storey stands on another floor
  std::string library_message;  // the last error CVODE reported
};

void unpack(const Floors& fl, const double* y, double* u, double* v) {
  for (int s = 0; s < fl.n(); ++s) {
    const int i = fl.floor_at(s);
    u[i] = y[2 * s];
    v[i] = y[2 * s + 1];
  }
}

int rhs(double t, N_Vector y, N_Vector ydot, void* data) {
  auto& pr = *static_cast<Problem*>(data);
  const Floors& fl = pr.floors;
  double* dy = N_VGetArrayPointer(ydot);
  unpack(fl, N_VGetArrayPointer(y), pr.u.data(), pr.v.data());
  std::fill(pr.f.begin(), pr.f.end(), 0.0);
  fl.add_forces(pr.u.data(), pr.v.data(), pr.f.data());
  const double ag = pr.load.accel(t);
  for (int s = 0; s < fl.n(); ++s) {
    const int i = fl.floor_at(s);
    const double spring = fl.spring(i, pr.u.data()), damper = fl.damper(i, pr.v.data());
    dy[2 * s] = pr.v[static_cast<std::size_t>(i)];
    dy[2 * s + 1] = (pr.f[static_cast<std::size_t>(i)] - spring - damper) / fl.mass(i) - ag;
  }
  return 0;
}

// Roots: every gap, every floor's velocity, every upper storey's drift rate.
int roots(double, N_Vector y, double* g, void* data) {
  auto& pr = *static_cast<Problem*>(data);
  const Floors& fl = pr.floors;
  unpack(fl, N_VGetArrayPointer(y), pr.u.data(), pr.v.data());
  const int nc = fl.nc(), n = fl.n();
  for (int j = 0; j < nc; ++j) g[j] = fl.gap(j, pr.u.data());
  for (int i = 0; i < n; ++i) g[nc + i] = pr.v[static_cast<std::size_t>(i)];
  for (std::size_t k = 0; k < pr.upper.size(); ++k) {
    const auto i = static_cast<std::size_t>(pr.upper[k]);
    g[static_cast<std::size_t>(nc + n) + k] = pr.v[i] - pr.v[i - 1];
  }
  return 0;
}

void keep_message(int, const char* module, const char* function, char* msg, void* data) {
  auto& pr = *static_cast<Problem*>(data);
  pr.library_message = std::string(module ? module : "") + "::" + (function ? function : "") + ": " + msg;
}

std::vector<double> zeros(int n) { return std::vector<double>(static_cast<std::size_t>(n), 0.0); }

std::vector<int> upper_floors(const BuildingModel& md) {
  std::vector<int> upper;
  for (int i = 0; i < md.n_floors; ++i)
    if (md.first[static_cast<std::size_t>(md.building_of[static_cast<std::size_t>(i)])] != i) upper.push_back(i);
  return upper;
}

class Run {
 public:
  Run(const BuildingModel& md, const Settings& set, Model element, double K)
      : md_(md),
        set_(set),
        floors_(md, element, K),
        n_(md.n_floors),
        nc_(floors_.nc()),
        neq_(static_cast<sunindextype>(2 * n_)),
        rtol_(set.rtol > 0.0 ? set.rtol : kDefaultRtol),
        cap_(set.step_cap > 0 ? set.step_cap : kDefaultCvodeStepCap),
        pr_{floors_, LoadCursor(md.scene.pulse), zeros(n_), zeros(n_), zeros(n_), upper_floors(md), {}},
        n_roots_(nc_ + n_ + static_cast<int>(pr_.upper.size())),
        found_(static_cast<std::size_t>(n_roots_), 0),
        values_(static_cast<std::size_t>(n_roots_), 0.0),
        peaks_(md),
        slack_(1e-10 * md.length_scale()) {}

  // CVODE made ready at rest at t = 0; what went wrong, else empty.
  std::string set_up(bool adams) {
    if (SUNContext_Create(nullptr, &cv_.context) != 0) return "SUNDIALS: no context";
    cv_.y = N_VNew_Serial(neq_, cv_.context);
    N_Vector atol = N_VNew_Serial(neq_, cv_.context);
    y_ = N_VGetArrayPointer(cv_.y);
    double* at = N_VGetArrayPointer(atol);
    for (sunindextype s = 0; s < n_; ++s) {
      y_[2 * s] = y_[2 * s + 1] = 0.0;
      // Lengths to rtol of a_p / w_p^2, velocities to rtol of a_p / w_p.
      at[2 * s] = rtol_ * md_.length_scale();
      at[2 * s + 1] = rtol_ * md_.length_scale() * md_.scene.pulse.w;
    }
    cv_.mem = CVodeCreate(adams ? CV_ADAMS : CV_BDF, cv_.context);
    CVodeSetErrHandlerFn(cv_.mem, keep_message, &pr_);  // a solver prints nothing
    int flag = CVodeInit(cv_.mem, rhs, 0.0, cv_.y);
    if (flag == CV_SUCCESS) flag = CVodeSVtolerances(cv_.mem, rtol_, atol);
    N_VDestroy(atol);
    if (flag == CV_SUCCESS) flag = CVodeSetUserData(cv_.mem, &pr_);
    // In y's entries: a floor's velocity row couples the u and v of floors up to half_band
    // slots away, 2 half_band + 1 entries either side (at least 3, the single oscillators' band).
    const sunindextype band = std::max<sunindextype>(3, 2 * floors_.half_band() + 1);
    cv_.band = SUNBandMatrix(neq_, band, band, cv_.context);
    cv_.linear = SUNLinSol_Band(cv_.y, cv_.band, cv_.context);
    if (flag == CV_SUCCESS) flag = CVodeSetLinearSolver(cv_.mem, cv_.linear, cv_.band);
    if (flag == CV_SUCCESS) flag = CVodeRootInit(cv_.mem, n_roots_, roots);
    if (flag == CV_SUCCESS) flag = CVodeSetNoInactiveRootWarn(cv_.mem);
    if (flag != CV_SUCCESS) return "CVODE set-up: " + flag_name(flag);
    return {};
  }

  // Steps to t_end, or until a status ends the run.
  buildings::BuildingsResult integrate() {
    const Pulse& pulse = md_.scene.pulse;
    peaks_.sample(0.0, pr_.u.data());
    dead_.emplace(set_);  // its clock started after the set-up, as the steps start
    const double t_pulse = std::min(pulse.duration(), md_.t_end);
    stop_ = !pulse.paper() ? next_stop(0.0) : t_pulse > 0.0 ? t_pulse : md_.t_end;
    CVodeSetStopTime(cv_.mem, stop_);
    while (t_ < md_.t_end && step()) {
    }
    res_.events = total_steps();
    res_.t_end = md_.t_end;
    peaks_.into(res_);
    return std::move(res_);
  }

 private:
  // One CVODE step (or root) and what it changed; false where the run ends before t_end (its
  // status set).
  bool step() {
    const int flag = CVode(cv_.mem, md_.t_end, cv_.y, &t_, CV_ONE_STEP);
    if (flag < 0) {
      res_.status = Status::failed;
      res_.message = "CVODE: " + flag_name(flag) + " at t = " + std::to_string(t_) +
                     (pr_.library_message.empty() ? "" : " (" + pr_.library_message + ")");
      return false;
    }
    unpack(floors_, y_, pr_.u.data(), pr_.v.data());
    bool finite = true;
    for (sunindextype i = 0; i < neq_; ++i) finite = finite && std::isfinite(y_[i]);
    const char* why = finite ? floors_.runaway(pr_.u.data(), pr_.v.data()) : "non-finite state";
    if (why) {
      res_.status = finite ? Status::diverged : Status::nan;
      res_.message = std::string(why) + " at t = " + std::to_string(t_);
      return false;
    }
    peaks_.sample(t_, pr_.u.data());
    bool changed = flag == CV_ROOT_RETURN && take_roots();
    changed = reconcile() || changed;
    if (flag == CV_TSTOP_RETURN && t_ < md_.t_end) {
      stop_ = md_.scene.pulse.paper() ? md_.t_end : next_stop(t_);
      changed = true;  // the load may jump at the pulse's end
    }
    if (changed && t_ < md_.t_end) restart();
    return within_limits();
  }

  // The gaps CVODE found closing or opening at this return; whether any did, or whether a rate
  // it found is exactly zero here. Floors that move alike (every floor at first, as the load
  // alone accelerates them) have a drift rate of exactly zero, step after step: CVODE reports
  // such a zero at a step's end as a root and then refuses it (CV_ILL_INPUT, "root found at
  // and very near t") unless the run restarts there, where it leaves a function that starts at
  // zero inactive until it moves.
  bool take_roots() {
    bool changed = false;
    CVodeGetRootInfo(cv_.mem, found_.data());
    for (int j = 0; j < nc_; ++j) {
      const int dir = found_[static_cast<std::size_t>(j)];
      if (dir < 0) floors_.close(j, floors_.q(j, pr_.v.data()), t_, peaks_), changed = true;
      if (dir > 0) floors_.open(j), changed = true;
    }
    if (changed) return true;
    roots(t_, cv_.y, values_.data(), &pr_);
    for (std::size_t r = static_cast<std::size_t>(nc_); r < found_.size(); ++r)
      if (found_[r] != 0 && values_[r] == 0.0) return true;
    return false;
  }

  // A contact whose state disagrees with its gap by more than round-off (one that closed at
  // t = 0 with a gap of 0, where CVODE ignores a root function that starts at zero).
  bool reconcile() {
    bool changed = false;
    for (int j = 0; j < nc_; ++j) {
      const double g = floors_.gap(j, pr_.u.data());
      if (!floors_.closed(j) && g < -slack_) floors_.close(j, floors_.q(j, pr_.v.data()), t_, peaks_), changed = true;
      if (floors_.closed(j) && g > slack_) floors_.open(j), changed = true;
    }
    return changed;
  }

  // The step cap and the time limit; false (the status set) where one has passed.
  bool within_limits() { return compliant::within_limits(total_steps(), cap_, *dead_, t_, res_); }

  long total_steps() const {
    long nst = 0;
    CVodeGetNumSteps(cv_.mem, &nst);
    return done_ + nst;
  }
  double next_stop(double from) const { return std::min(md_.scene.pulse.next_break(from), md_.t_end); }
  void restart() {
    done_ = total_steps();
    CVodeReInit(cv_.mem, t_, cv_.y);
    CVodeSetStopTime(cv_.mem, stop_);
  }

  const BuildingModel& md_;
  const Settings& set_;
  Floors floors_;
  const int n_, nc_;
  const sunindextype neq_;
  const double rtol_;
  const long cap_;
  Problem pr_;
  const int n_roots_;
  std::vector<int> found_;
  std::vector<double> values_;  // the root functions at a return
  buildings::FloorPeaks peaks_;
  const double slack_;
  std::optional<Deadline> dead_;
  Cvode cv_;
  double* y_ = nullptr;  // cv_.y's entries
  buildings::BuildingsResult res_;
  long done_ = 0;  // the steps of the segments before the last restart
  double t_ = 0.0, stop_ = 0.0;
};

}  // namespace

}  // namespace pb::compliant::building_cvode

namespace pb::compliant {

buildings::BuildingsResult run_buildings_cvode(const BuildingModel& model, const Settings& settings, Model element,
                                               double K, bool adams) {
  building_cvode::Run run(model, settings, element, K);
  if (std::string why = run.set_up(adams); !why.empty()) {
    buildings::BuildingsResult r;
    r.status = Status::failed;
    r.message = std::move(why);
    r.t_end = model.t_end;
    return r;
  }
  return run.integrate();
}

}  // namespace pb::compliant
