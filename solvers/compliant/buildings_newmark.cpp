// The compliant solver's newmark integrator on the buildings scene (buildings.hpp): average
// acceleration (gamma 1/2, beta 1/4) at the fixed step h = t_min / N, as OpenSees runs a model
// of zeroLength contact elements (`integrator Newmark 0.5 0.25`, `algorithm Newton`). Each
// (sub-)step solves the equation of motion at its end for u by Newton's method,
//
//   a = 4/h^2 (u - u_n) - 4/h v_n - a_n      v = 2/h (u - u_n) - v_n
//   R(u) = M a + C v + K u + M 1 a_g(t_n+1) - W F(u, v) = 0,
//
// whose Jacobian 4/h^2 M + 2/h C + K plus each closed element's dF/dp + 2/h dF/dq between its two
// floors is symmetric positive definite and banded in the floors' level-by-level order
// (floors.hpp): factored by a banded Cholesky into buffers made once per run, so a step
// allocates nothing. The step is split where the load jumps and where an element opens or
// closes, exactly as the single oscillators' engine splits it (newmark.cpp, step_split.hpp):
// every (sub-)step sees one smooth force law per element, and the cubic Hermite interpolant of
// each penetration locates a change to O(h^3): second order overall. The peaks are read at
// the steps' ends k h only (FloorPeaks), as every time-stepper's are.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "cases/system.hpp"
#include "kit/fixed_step.hpp"
#include "kit/run_limits.hpp"
#include "solvers/compliant/buildings.hpp"
#include "solvers/compliant/floors.hpp"
#include "solvers/compliant/step_split.hpp"

namespace pb::compliant::building_newmark {

namespace {

// The lower band of a symmetric positive definite matrix, half band b, and its Cholesky factor
// in place.
class BandCholesky {
 public:
  BandCholesky(int n, int b) : n_(n), b_(b), a_(static_cast<std::size_t>(n) * static_cast<std::size_t>(b + 1), 0.0) {}
  void clear() { std::fill(a_.begin(), a_.end(), 0.0); }
  // Entry (i, j), j <= i <= j + b.
  double& at(int i, int j) { return a_[index(i, j)]; }
  double at(int i, int j) const { return a_[index(i, j)]; }
  // False where a pivot is not positive.
  bool factor() {
    for (int i = 0; i < n_; ++i) {
      const int k0 = std::max(0, i - b_);
      for (int j = k0; j <= i; ++j) {
        double s = at(i, j);
        for (int k = k0; k < j; ++k) s -= at(i, k) * at(j, k);
        if (j < i) {
          at(i, j) = s / at(j, j);
        } else {
          if (!(s > 0.0)) return false;
          at(i, i) = std::sqrt(s);
        }
      }
    }
    return true;
  }
  // x = J^-1 x, J factored.
  void solve(double* x) const {
    for (int i = 0; i < n_; ++i) {
      double s = x[i];
      for (int k = std::max(0, i - b_); k < i; ++k) s -= at(i, k) * x[k];
      x[i] = s / at(i, i);
    }
    for (int i = n_ - 1; i >= 0; --i) {
      double s = x[i];
      for (int k = i + 1; k <= std::min(n_ - 1, i + b_); ++k) s -= at(k, i) * x[k];
      x[i] = s / at(i, i);
    }
  }

 private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(i) * static_cast<std::size_t>(b_ + 1) + static_cast<std::size_t>(i - j);
  }
  int n_, b_;
  std::vector<double> a_;
};

class Engine {
 public:
  Engine(const BuildingModel& md, Floors& floors, buildings::FloorPeaks& peaks, double h)
      : md_(md),
        fl_(floors),
        peaks_(peaks),
        load_(md.scene.pulse),
        h_(h),
        n_(md.n_floors),
        nc_(floors.nc()),
        jumps_(load_jumps(md.scene.pulse)),
        jac_(n_, floors.half_band()) {
    for (std::vector<double>* x : {&u_, &v_, &a_, &un_, &vn_, &f_, &res_}) x->assign(static_cast<std::size_t>(n_), 0.0);
    // As LoadCursor::sample treats the load's end: within 1e-9 max(h, T) of a step's end, a
    // jump is at that end (so that T_p = N h ends the pulse on a boundary however N h rounds).
    for (const LoadJump& j : jumps_) jump_tol_ = std::max(jump_tol_, 1e-9 * std::max(h, j.t));
    // The start's acceleration from the equation of motion itself (at rest, no element closed).
    const double ag = md.scene.pulse.accel(0.0);
    for (int i = 0; i < n_; ++i)
      a_[ix(i)] = (f_[ix(i)] - fl_.spring(i, u_.data()) - fl_.damper(i, v_.data())) / md.m(i) - ag;
  }

  const std::vector<double>& u() const { return u_; }
  const std::vector<double>& v() const { return v_; }

  // The step from k h to (k + 1) h; false, with `why`, where it could not be taken.
  bool step(long k, std::string& why) {
    const double t0 = static_cast<double>(k) * h_, t1 = static_cast<double>(k + 1) * h_;
    while (next_jump_ < jumps_.size() && jumps_[next_jump_].t <= t0 + jump_tol_) ++next_jump_;
    const LoadJump* jump = next_jump_ < jumps_.size() ? &jumps_[next_jump_] : nullptr;
    // A jump strictly inside the step splits it there: to the jump under the load before it,
    // then on from the acceleration of the load after it.
    if (jump && jump->t > t0 + jump_tol_ && jump->t < t1 - jump_tol_) {
      if (!advance(jump->t - t0, jump->t, jump->before, why)) return false;
      restart(*jump);
      return advance(t1 - jump->t, t1, load_.sample(t1, h_), why);
    }
    const bool at_jump = jump && std::abs(jump->t - t1) <= jump_tol_;
    if (!advance(h_, t1, at_jump ? jump->before : load_.sample(t1, h_), why)) return false;
    if (at_jump) restart(*jump);
    return true;
  }

 private:
  static std::size_t ix(int i) { return static_cast<std::size_t>(i); }

  // From the state over h to t1, where the load is ag (continuous in between): (sub-)steps
  // that end where an element opens or closes, so that each sees one smooth force law.
  bool advance(double h, double t1, double ag, std::string& why) {
    double left = h;  // to t1
    for (int events = 0;; ++events) {
      un_ = u_;
      vn_ = v_;
      if (!solve(left, ag)) return newton_failed(t1, why);
      int which = -1;
      const double theta = first_event(left, which);
      if (which < 0) {
        commit(left);
        return true;
      }
      if (events == kMaxEventsPerStep) {
        why = "more than " + std::to_string(kMaxEventsPerStep) + " contact changes in the step to t = " +
              std::to_string(t1) + " (a step too large for the contact stiffness)";
        return false;
      }
      u_ = un_;  // redo the step to the event
      v_ = vn_;
      const double part = theta * left, te = t1 - left + part;
      if (part > kTinyFraction * h_) {
        if (!solve(part, load_.accel(te))) return newton_failed(te, why);
        commit(part);
        left -= part;
      }
      switch_element(which, te);
    }
  }

  static bool newton_failed(double t, std::string& why) {
    why = "Newton's iteration on the contact forces did not converge in " + std::to_string(kNewtonIterations) +
          " iterations at t = " + std::to_string(t) + " (a step too large for the contact stiffness)";
    return false;
  }

  // The acceleration at the jump from the load after it: each floor feels -a_g, so a changes by
  // the jump alone.
  void restart(const LoadJump& jump) {
    for (double& a : a_) a -= jump.after - jump.before;
  }

  // Newton's iteration for one (sub-)step of length h from (un_, vn_, a_) under the load ag at
  // its end, every element in the state it starts in: u_, v_ at its end. False when it does
  // not converge.
  bool solve(double h, double ag) {
    const double c_a = 4.0 / (h * h), c_v = 2.0 / h;
    for (int i = 0; i < n_; ++i) u_[ix(i)] = un_[ix(i)] + h * vn_[ix(i)] + 0.25 * h * h * a_[ix(i)];
    for (int it = 0; it < kNewtonIterations; ++it) {
      for (int i = 0; i < n_; ++i) v_[ix(i)] = c_v * (u_[ix(i)] - un_[ix(i)]) - vn_[ix(i)];
      forces();
      double scale = md_.length_scale();
      for (int i = 0; i < n_; ++i) {
        const double m = md_.m(i), acc = c_a * (u_[ix(i)] - un_[ix(i)]) - 2.0 * c_v * vn_[ix(i)] - a_[ix(i)];
        res_[ix(fl_.slot_of(i))] =
            m * acc + fl_.damper(i, v_.data()) + fl_.spring(i, u_.data()) + m * ag - f_[ix(i)];
        scale = std::max(scale, std::abs(u_[ix(i)]));
      }
      assemble(c_a, c_v);
      if (!jac_.factor()) return false;
      jac_.solve(res_.data());
      double largest = 0.0;
      for (int i = 0; i < n_; ++i) {
        const double du = res_[ix(fl_.slot_of(i))];
        u_[ix(i)] -= du;
        largest = std::max(largest, std::abs(du));
      }
      if (largest <= kNewtonTolerance * scale) {
        for (int i = 0; i < n_; ++i) v_[ix(i)] = c_v * (u_[ix(i)] - un_[ix(i)]) - vn_[ix(i)];
        return true;
      }
    }
    return false;
  }

  // The Jacobian c_a M + c_v C + K and each closed element's dF/dp + c_v dF/dq between its two
  // floors, in slots (its lower band).
  void assemble(double c_a, double c_v) {
    jac_.clear();
    for (int i = 0; i < n_; ++i) {
      const int si = fl_.slot_of(i);
      jac_.at(si, si) += c_a * md_.m(i);
      for (const Floors::Entry& e : fl_.row(i)) {
        const int sc = fl_.slot_of(e.col);
        if (sc <= si) jac_.at(si, sc) += e.k + c_v * e.c;
      }
    }
    for (int j = 0; j < nc_; ++j) {
      if (!fl_.closed(j)) continue;
      const Law& law = fl_.law(j);
      double dp = law.k, dq = law.c;  // Kelvin-Voigt's linear law, through p = 0 too
      if (law.model != Model::kelvin_voigt)
        law.slopes(fl_.p(j, u_.data()), fl_.q(j, v_.data()), fl_.v_minus(j), dp, dq);
      const double kappa = dp + c_v * dq;
      const int sl = fl_.slot_of(fl_.left(j)), sr = fl_.slot_of(fl_.right(j));
      jac_.at(sl, sl) += kappa;
      jac_.at(sr, sr) += kappa;
      jac_.at(std::max(sl, sr), std::min(sl, sr)) -= kappa;
    }
  }

  // The (sub-)step of length h just solved becomes the state: its acceleration.
  void commit(double h) {
    const double c_a = 4.0 / (h * h), c_v = 2.0 / h;
    for (int i = 0; i < n_; ++i) a_[ix(i)] = c_a * (u_[ix(i)] - un_[ix(i)]) - 2.0 * c_v * vn_[ix(i)] - a_[ix(i)];
  }

  // Contact j changes state at time t: closes (an impact if approaching) or opens. Its force
  // jumps there (Kelvin-Voigt's by c q), and each floor's acceleration by that jump over its
  // mass alone, as at the load's jump.
  void switch_element(int j, double t) {
    const double before = element_force(j), q = fl_.q(j, v_.data());
    if (fl_.closed(j))
      fl_.open(j);
    else
      fl_.close(j, q, t, peaks_);
    const double jump = element_force(j) - before;
    a_[ix(fl_.right(j))] += jump / md_.m(fl_.right(j));
    a_[ix(fl_.left(j))] -= jump / md_.m(fl_.left(j));
  }

  // Contact j's force at the state in the state it is in: a closed Kelvin-Voigt element keeps
  // its linear law through p = 0 (its end is an event, not a clamp), the others their own.
  double element_force(int j) const {
    if (!fl_.closed(j)) return 0.0;
    const Law& law = fl_.law(j);
    const double p = fl_.p(j, u_.data()), q = fl_.q(j, v_.data());
    return law.model == Model::kelvin_voigt ? law.k * p + law.c * q : law.force(p, q, fl_.v_minus(j));
  }

  // The element forces on the floors at the state.
  void forces() {
    std::fill(f_.begin(), f_.end(), 0.0);
    for (int j = 0; j < nc_; ++j) {
      if (!fl_.closed(j)) continue;
      const double F = element_force(j);
      f_[ix(fl_.right(j))] += F;
      f_[ix(fl_.left(j))] -= F;
    }
  }

  // Over the (sub-)step of length h just solved (un_, vn_ to the state), the first fraction at
  // which an element's state stops matching its motion, and that element in `which` (-1, and 2
  // returned, when none).
  double first_event(double h, int& which) const {
    double first = 2.0;
    which = -1;
    for (int j = 0; j < nc_; ++j) {
      const PenetrationCubic c{fl_.p(j, un_.data()), fl_.q(j, vn_.data()), fl_.p(j, u_.data()), fl_.q(j, v_.data()), h,
                               fl_.closed(j) ? -1.0 : 1.0};
      const double theta = c.first_mismatch(first);
      if (theta < first) first = theta, which = j;
    }
    return first;
  }

  const BuildingModel& md_;
  Floors& fl_;
  buildings::FloorPeaks& peaks_;
  LoadCursor load_;  // a_g at each step's end, O(1) on a record
  double h_;
  int n_, nc_;
  std::vector<double> u_, v_, a_, un_, vn_, f_;  // per floor, global order
  std::vector<double> res_;                       // per slot: the residual, then the correction
  std::vector<LoadJump> jumps_;                   // in time order
  std::size_t next_jump_ = 0;                     // the first not yet passed
  double jump_tol_ = 0.0;
  BandCholesky jac_;
};

// The steps to t_end, each sampled for the peaks; the status where one ended the run.
void step_through(const BuildingModel& md, const Settings& set, Engine& engine, const Floors& fl, long n, double h,
               buildings::FloorPeaks& peaks, buildings::BuildingsResult& res) {
  peaks.sample(0.0, engine.u().data());
  Deadline deadline(set);
  long k = 0;
  while (k < n) {
    if (!engine.step(k, res.message)) {
      res.status = Status::failed;
      break;
    }
    ++k;
    const double t = static_cast<double>(k) * h;
    const double* u = engine.u().data();
    const double* v = engine.v().data();
    bool finite = true;
    for (int i = 0; i < md.n_floors; ++i) finite = finite && std::isfinite(u[i]) && std::isfinite(v[i]);
    if (const char* why = finite ? fl.runaway(u, v) : "non-finite state") {
      res.status = finite ? Status::diverged : Status::nan;
      res.message = std::string(why) + " at t = " + std::to_string(t);
      break;
    }
    peaks.sample(t, u);
    if (k < n && deadline.passed(k)) {
      res.status = Status::time_limit;
      res.message = deadline.reason() + " at t = " + std::to_string(t);
      break;
    }
  }
  res.events = k;
}

}  // namespace

}  // namespace pb::compliant::building_newmark

namespace pb::compliant {

buildings::BuildingsResult run_buildings_newmark(const BuildingModel& md, const Settings& set, Model element,
                                                 double K) {
  buildings::BuildingsResult res;
  long n = 0;
  if (!buildings::plan_steps(md, set, kDefaultSteps, res, n)) return res;
  const double h = res.step;
  Floors floors(md, element, K);
  buildings::FloorPeaks peaks(md);
  building_newmark::Engine engine(md, floors, peaks, h);
  building_newmark::step_through(md, set, engine, floors, n, h, peaks, res);
  peaks.into(res);
  return res;
}

}  // namespace pb::compliant
