// The newmark integrator of the compliant solver (compliant.hpp): average acceleration
// (gamma 1/2, beta 1/4) at a fixed step, one engine of the shared fixed-step shell. Each
// (sub-)step solves the equation of motion at its end for u with Newton's method:
//
//   a = 4/h^2 (u - u_n) - 4/h v_n - a_n      v = 2/h (u - u_n) - v_n
//   R(u) = M a + C v + K u + M a_g(t_n+1) - W F(u, v) = 0
//
// Every element acts like a spring of stiffness dF/dp + 2/h dF/dq between its two bodies in
// the Jacobian, which is therefore tridiagonal (bodies in a row, each tied to the ground by
// its own spring and dashpot): solved by the Thomas algorithm into buffers held by the
// engine, so a step allocates nothing.
//
// Where a contact begins or ends, its force law is not smooth (the Kelvin-Voigt force jumps
// by c q; the Hertz family's has a kink), and the trapezoidal rule integrates a jump to O(h):
// Newmark converged erratically, at first order (K = 1e3 against the exact solution: Pi1
// 2.7e-4 at N = 1024, 4.6e-4 at 4096). So a step is split there, as it is at the load's jump:
// each (sub-)step is solved with every element kept in the state it starts in (a closed
// Kelvin-Voigt element keeps its linear law k p + c q through p = 0, the others their force,
// zero there), so its law is smooth; the cubic Hermite interpolant of each penetration over
// the solved step then locates the first time an element's state stops matching its motion
// (open, yet overlapping and approaching; closed, yet apart and parting). The step is redone
// to that time, the element switched there (each body's acceleration changing by the
// element's force jump alone), and the rest solved from there. The interpolant places the
// event to O(h^3) in the penetration: an O(h^3) error per contact change, second order overall
// (solvers/compliant/newmark_order_test.cpp: body 0's state at 1.94 to 2.00 from N = 512 to 8192, before
// 0.58 to 1.68). A sub-step's end is not a step's end of the run: the shell reads Pi1, the
// history and the tallies at t = k h only (cases/README.md: the largest |u0| over the steps of
// h = T_min / N), so the sampled maximum means what it means for every time-stepper, and a run
// in which no contact changes is bit for bit what it was.
// Rejected: pinning the gap at zero by a set-valued force where Newton's iterates flip an
// element open and closed (what this replaced): it converges, but at first order.
//
// Where the load jumps (load_jumps below), a step is split at the jump, and the step after it
// starts from the acceleration of the load after it: second order across it.
//
// A yielding body's spring is the bilinear law's return map at the iterate (hysteresis.hpp):
// its force and its slope, k or alpha k, enter R and the Jacobian as OpenSees' Newton runs a
// Steel01 material with hardening; the step's end commits its z. Its force is continuous at
// yield and at unloading (only its slope changes): the trapezoidal rule's error there is
// O(h^2) in the velocity once per yield, second order overall, and the step is not split.

#include <cmath>
#include <string>
#include <vector>

#include "solvers/compliant/integrators.hpp"
#include "solvers/compliant/step_split.hpp"
#include "kit/contact_elements/elements.hpp"
#include "kit/fixed_step.hpp"
#include "kit/hysteresis.hpp"

namespace pb::compliant {

namespace {

class NewmarkEngine final : public StepEngine {
 public:
  NewmarkEngine(const System& sys, Elements& elements, double h)
      : StepEngine(sys), sys_(sys), load_(sys.pulse), el_(elements), h_(h), n_(sys.n_bodies()), nc_(sys.n_contacts()) {
    const auto nb = ix(n_);
    a_.assign(nb, 0.0);
    un_.assign(nb, 0.0);
    vn_.assign(nb, 0.0);
    res_.assign(nb, 0.0);
    diag_.assign(nb, 0.0);
    upper_.assign(nb, 0.0);
    du_.assign(nb, 0.0);
    f_.assign(nb, 0.0);
    mult_.assign(nb, 0.0);
    start_u_ = out_.u;
    start_v_ = out_.v;
    jumps_ = load_jumps(sys.pulse);
    // As LoadCursor::sample treats the load's end: within 1e-9 max(h, T) of a step's end, a
    // jump is at that end (so that T_p = N h ends the pulse on a boundary however N h rounds).
    for (const LoadJump& j : jumps_) jump_tol_ = std::max(jump_tol_, 1e-9 * std::max(h, j.t));
    zn_ = out_.u;  // z = u: at rest a yielding body's z is 0, and an elastic body's is its u
    // The start's acceleration from the equation of motion itself.
    forces(out_.u, out_.v);
    const double ag = sys.pulse.accel(0.0);
    for (int i = 0; i < n_; ++i) {
      const Body& b = sys.bodies[ix(i)];
      const double spring = return_map(b, sys.alpha, zn_[ix(i)], out_.u[ix(i)], 0.0).force;
      a_[ix(i)] = (f_[ix(i)] - spring - b.c * out_.v[ix(i)]) / b.m - ag;
    }
    ag_n_ = ag;
  }

  StepOutcome step(long k, Result& res) override {
    const double t0 = static_cast<double>(k) * h_, t1 = static_cast<double>(k + 1) * h_;
    while (next_jump_ < jumps_.size() && jumps_[next_jump_].t <= t0 + jump_tol_) ++next_jump_;
    const LoadJump* jump = next_jump_ < jumps_.size() ? &jumps_[next_jump_] : nullptr;
    std::fill(out_.entered.begin(), out_.entered.end(), 0);
    start_u_ = out_.u;
    start_v_ = out_.v;
    // A jump strictly inside the step splits it there: to the jump under the load before it,
    // then on from the acceleration of the load after it.
    bool ok;
    if (jump && jump->t > t0 + jump_tol_ && jump->t < t1 - jump_tol_) {
      ok = advance(jump->t - t0, jump->t, jump->before, res);
      if (ok) {
        restart(*jump);
        ok = advance(t1 - jump->t, t1, load_.sample(t1, h_), res);
      }
    } else {
      const bool at_jump = jump && std::abs(jump->t - t1) <= jump_tol_;
      ok = advance(h_, t1, at_jump ? jump->before : load_.sample(t1, h_), res);
      if (ok && at_jump) restart(*jump);
    }
    if (!ok) {
      out_.u = start_u_;
      out_.v = start_v_;
      return StepOutcome::refused;
    }
    return StepOutcome::taken;
  }

  // From out_ over h to t1, where the load is ag (continuous in between): (sub-)steps that
  // end where an element opens or closes, so that each sees one smooth force law. False,
  // with res saying why, when Newton's iteration fails or the step holds too many changes.
  bool advance(double h, double t1, double ag, Result& res) {
    double left = h;  // to t1
    for (int events = 0;; ++events) {
      un_ = out_.u;
      vn_ = out_.v;
      if (!solve(left, ag)) return failed(res, t1);
      int which = -1;
      const double theta = first_event(left, which);
      if (which < 0) {
        commit(left, ag);
        return true;
      }
      if (events == kMaxEventsPerStep) {
        res.status = Status::failed;
        res.message = "more than " + std::to_string(kMaxEventsPerStep) + " contact changes in the step to t = " +
                      std::to_string(t1) + " (a step too large for the contact stiffness)";
        return false;
      }
      out_.u = un_;  // redo the step to the event
      out_.v = vn_;
      const double part = theta * left, te = t1 - left + part;
      if (part > kTinyFraction * h_) {
        const double ag_e = load_.accel(te);
        if (!solve(part, ag_e)) return failed(res, te);
        commit(part, ag_e);
        left -= part;
      }
      switch_element(which, te);
    }
  }

  // The acceleration at the jump from the load after it: each body feels -a_g, so a changes
  // by the jump alone (the springs, dashpots and elements are where the step left them).
  void restart(const LoadJump& jump) {
    for (double& a : a_) a -= jump.after - jump.before;
    ag_n_ = jump.after;  // the yield tally's trapezoid then starts from the load after it
  }

  bool contacts_have_duration() const override { return true; }

  void finish(Result& res) override {
    res.impacts = el_.impacts();
    res.contact_phases = 0;
    el_.finish(res);  // restitution over whole contacts, not over one step
    if (sys_.yields()) yield_tally_.finish(sys_, out_.u[ix(sys_.ref)], zn_[ix(sys_.ref)], res);
  }

 private:
  bool failed(Result& res, double t) const {
    res.status = Status::failed;
    res.message = "Newton's iteration on the contact forces did not converge in " +
                  std::to_string(kNewtonIterations) + " iterations at t = " + std::to_string(t) +
                  " (a step too large for the contact stiffness)";
    return false;
  }

  // Newton's iteration for one (sub-)step of length h from (un_, vn_, a_) under the load ag at
  // its end, every element in the state it starts in: out_.u, out_.v at its end. False when it
  // does not converge.
  bool solve(double h, double ag) {
    std::vector<double>& u = out_.u;
    std::vector<double>& v = out_.v;
    const double c_a = 4.0 / (h * h), c_v = 2.0 / h;
    // Predictor: constant acceleration.
    for (int i = 0; i < n_; ++i) u[ix(i)] = un_[ix(i)] + h * vn_[ix(i)] + 0.25 * h * h * a_[ix(i)];
    for (int it = 0; it < kNewtonIterations; ++it) {
      for (int i = 0; i < n_; ++i) v[ix(i)] = c_v * (u[ix(i)] - un_[ix(i)]) - vn_[ix(i)];
      forces(u, v);
      double scale = sys_.length_scale();
      for (int i = 0; i < n_; ++i) {
        const Body& b = sys_.bodies[ix(i)];
        const double acc = c_a * (u[ix(i)] - un_[ix(i)]) - 2.0 * c_v * vn_[ix(i)] - a_[ix(i)];
        const Hysteresis spring = return_map(b, sys_.alpha, zn_[ix(i)], u[ix(i)], u[ix(i)] - un_[ix(i)]);
        res_[ix(i)] = b.m * acc + b.c * v[ix(i)] + spring.force + b.m * ag - f_[ix(i)];
        diag_[ix(i)] = c_a * b.m + c_v * b.c + spring.tangent;
        upper_[ix(i)] = 0.0;
        scale = std::max(scale, std::abs(u[ix(i)]));
      }
      add_element_slopes(u, v, c_v);
      if (!factor_tridiagonal()) return false;
      solve_factored(res_, du_);
      double largest = 0.0;
      for (int i = 0; i < n_; ++i) {
        u[ix(i)] -= du_[ix(i)];
        largest = std::max(largest, std::abs(du_[ix(i)]));
      }
      if (largest <= kNewtonTolerance * scale) {
        for (int i = 0; i < n_; ++i) v[ix(i)] = c_v * (u[ix(i)] - un_[ix(i)]) - vn_[ix(i)];
        return true;
      }
    }
    return false;
  }

  // Each closed element's dF/dp + c_v dF/dq in the Jacobian, between its two bodies.
  void add_element_slopes(const std::vector<double>& u, const std::vector<double>& v, double c_v) {
    for (int j = 0; j < nc_; ++j) {
      if (!el_.closed(j)) continue;
      const Law& law = el_.law(j);
      double dp = law.k, dq = law.c;  // Kelvin-Voigt's linear law, through p = 0 too
      if (law.model != Model::kelvin_voigt) law.slopes(el_.p(j, u.data()), el_.q(j, v.data()), el_.v_minus(j), dp, dq);
      const double kappa = dp + c_v * dq;
      const int r = sys_.right(j), l = sys_.left(j);
      diag_[ix(r)] += kappa;
      if (l != kWall) {
        diag_[ix(l)] += kappa;
        upper_[ix(l)] -= kappa;  // (l, l + 1) and (l + 1, l): contacts join neighbours
      }
    }
  }

  // The (sub-)step of length h just solved becomes the state: its acceleration, the yielding
  // bodies' z and tally, the load at its end, the elements' forces there.
  void commit(double h, double ag) {
    const std::vector<double>& u = out_.u;
    const std::vector<double>& v = out_.v;
    const double c_a = 4.0 / (h * h), c_v = 2.0 / h;
    for (int i = 0; i < n_; ++i) a_[ix(i)] = c_a * (u[ix(i)] - un_[ix(i)]) - 2.0 * c_v * vn_[ix(i)] - a_[ix(i)];
    if (sys_.yields()) {
      for (int i = 0; i < n_; ++i) {
        const double du = u[ix(i)] - un_[ix(i)];
        const Hysteresis spring = return_map(sys_.bodies[ix(i)], sys_.alpha, zn_[ix(i)], u[ix(i)], du);
        yield_tally_.step(sys_, i, 0.5 * (ag_n_ + ag), du, spring);  // the load's trapezoid
        zn_[ix(i)] = spring.z;
      }
    }
    ag_n_ = ag;
    for (int j = 0; j < nc_; ++j) out_.force[ix(j)] = element_force(j, u.data(), v.data());
  }

  // Contact j changes state at time t, at the state out_: closes (an impact if approaching) or
  // opens. Its force jumps there (Kelvin-Voigt's by c q), and each body's acceleration by
  // that jump over its mass alone, as at the load's jump.
  void switch_element(int j, double t) {
    const double* u = out_.u.data();
    const double* v = out_.v.data();
    const double before = element_force(j, u, v), q = el_.q(j, v);
    if (el_.closed(j)) {
      el_.open(j, q);
    } else {
      el_.close(j, q, t);
      out_.entered[ix(j)] = 1;
    }
    const double jump = element_force(j, u, v) - before;
    const int r = sys_.right(j), l = sys_.left(j);
    a_[ix(r)] += jump / sys_.bodies[ix(r)].m;
    if (l != kWall) a_[ix(l)] -= jump / sys_.bodies[ix(l)].m;
    out_.force[ix(j)] = element_force(j, u, v);
  }

  // Contact j's force in the state it is in: a closed Kelvin-Voigt element keeps its linear
  // law through p = 0 (its end is an event, not a clamp), the others their own (zero there).
  double element_force(int j, const double* u, const double* v) const {
    if (!el_.closed(j)) return 0.0;
    const Law& law = el_.law(j);
    const double p = el_.p(j, u), q = el_.q(j, v);
    return law.model == Model::kelvin_voigt ? law.k * p + law.c * q : law.force(p, q, el_.v_minus(j));
  }

  // The element forces on the bodies at (u, v).
  void forces(const std::vector<double>& u, const std::vector<double>& v) {
    std::fill(f_.begin(), f_.end(), 0.0);
    for (int j = 0; j < nc_; ++j) {
      if (!el_.closed(j)) continue;
      const double F = element_force(j, u.data(), v.data());
      f_[ix(sys_.right(j))] += F;
      if (sys_.left(j) != kWall) f_[ix(sys_.left(j))] -= F;
    }
  }

  // Over the (sub-)step of length h just solved (un_, vn_ to out_), the first fraction at which
  // an element's state stops matching its motion, on the cubic Hermite interpolant of its
  // penetration, and that element in `which` (-1, and 2 returned, when none).
  double first_event(double h, int& which) const {
    double first = 2.0;
    which = -1;
    for (int j = 0; j < nc_; ++j) {
      const PenetrationCubic c{el_.p(j, un_.data()), el_.q(j, vn_.data()), el_.p(j, out_.u.data()),
                               el_.q(j, out_.v.data()), h, el_.closed(j) ? -1.0 : 1.0};
      const double theta = c.first_mismatch(first);
      if (theta < first) first = theta, which = j;
    }
    return first;
  }

  // The Thomas factorisation of J, symmetric tridiagonal (diag_, upper_), in place: the
  // eliminated diagonal, and each row's multiplier in mult_. False if a pivot vanished.
  bool factor_tridiagonal() {
    for (int i = 1; i < n_; ++i) {
      if (!(std::abs(diag_[ix(i - 1)]) > 0.0)) return false;
      mult_[ix(i)] = upper_[ix(i - 1)] / diag_[ix(i - 1)];
      diag_[ix(i)] -= mult_[ix(i)] * upper_[ix(i - 1)];
    }
    return std::abs(diag_[ix(n_ - 1)]) > 0.0;
  }

  // x = J^-1 b with J factored (b is overwritten).
  void solve_factored(std::vector<double>& b, std::vector<double>& x) const {
    for (int i = 1; i < n_; ++i) b[ix(i)] -= mult_[ix(i)] * b[ix(i - 1)];
    for (int i = n_; i-- > 0;)
      x[ix(i)] = (b[ix(i)] - (i + 1 < n_ ? upper_[ix(i)] * x[ix(i + 1)] : 0.0)) / diag_[ix(i)];
  }

  const System& sys_;
  LoadCursor load_;  // a_g at each step's end, O(1) on a record
  Elements& el_;
  double h_;
  int n_, nc_;
  std::vector<double> a_, un_, vn_, res_, diag_, upper_, mult_, du_, f_;
  std::vector<double> start_u_, start_v_;  // the state at the step's start, for a refused step
  std::vector<LoadJump> jumps_;            // in time order
  std::size_t next_jump_ = 0;              // the first not yet passed
  double jump_tol_ = 0.0;
  std::vector<double> zn_;  // per body: the hysteretic variable at the step's start
  HystereticTally yield_tally_;
  double ag_n_ = 0.0;  // a_g at the step's start
};

}  // namespace

Result run_newmark(const System& sys, const Settings& set, Model model, double K) {
  StepPlan plan;
  if (Result r = plan_steps(sys, set, kDefaultSteps, kDefaultStepCap, plan); r.status != Status::ok) return r;
  Elements elements(sys, model, K);
  NewmarkEngine engine(sys, elements, plan.h);
  return run_steps(sys, set, plan, engine);
}

}  // namespace pb::compliant
