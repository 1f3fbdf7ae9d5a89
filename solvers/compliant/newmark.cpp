// The newmark integrator of the compliant solver (compliant.hpp): average acceleration
// (gamma 1/2, beta 1/4) at a fixed step, one engine of the shared fixed-step shell. Each
// step solves the equation of motion at its end for u with Newton's method:
//
//   a = 4/h^2 (u - u_n) - 4/h v_n - a_n      v = 2/h (u - u_n) - v_n
//   R(u) = M a + C v + K u + M a_g(t_n+1) - W F(u, v) = 0
//
// Every element acts like a spring of stiffness dF/dp + 2/h dF/dq between its two bodies in
// the Jacobian, which is therefore tridiagonal (bodies in a row, each tied to the ground by
// its own spring and dashpot): solved by the Thomas algorithm into buffers held by the
// engine, so a step allocates nothing. An element acts while its penetration at the
// iterate is positive; a closing contact takes its approach rate at the step's start.

#include <cmath>
#include <string>
#include <vector>

#include "solvers/compliant/elements.hpp"
#include "solvers/compliant/integrators.hpp"
#include "solvers/fixed_step.hpp"

namespace pb::compliant {

namespace {

std::size_t ix(int i) { return static_cast<std::size_t>(i); }

// Iterations before a step is given up, and the correction (over a_p / w_p^2 plus the
// largest |u|) below which an iterate counts as converged.
constexpr int kNewtonIterations = 50;
constexpr double kNewtonTolerance = 1e-13;

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
    vm_.assign(ix(nc_), 0.0);
    closed_.assign(ix(nc_), 0);
    onset_rates();
    // The start's acceleration from the equation of motion itself.
    forces(out_.u, out_.v);
    const double ag = sys.pulse.accel(0.0);
    for (int i = 0; i < n_; ++i) {
      const Body& b = sys.bodies[ix(i)];
      a_[ix(i)] = (f_[ix(i)] - b.k * out_.u[ix(i)] - b.c * out_.v[ix(i)]) / b.m - ag;
    }
  }

  StepOutcome step(long k, Result& res) override {
    std::vector<double>& u = out_.u;
    std::vector<double>& v = out_.v;
    un_ = u;
    vn_ = v;
    onset_rates();
    const double t1 = static_cast<double>(k + 1) * h_;
    const double ag = load_.sample(t1, h_);
    const double c_a = 4.0 / (h_ * h_), c_v = 2.0 / h_;
    // Predictor: constant acceleration.
    for (int i = 0; i < n_; ++i) u[ix(i)] = un_[ix(i)] + h_ * vn_[ix(i)] + 0.25 * h_ * h_ * a_[ix(i)];
    bool converged = false;
    for (int it = 0; it < kNewtonIterations && !converged; ++it) {
      for (int i = 0; i < n_; ++i) v[ix(i)] = c_v * (u[ix(i)] - un_[ix(i)]) - vn_[ix(i)];
      forces(u, v);
      double scale = sys_.length_scale();
      for (int i = 0; i < n_; ++i) {
        const Body& b = sys_.bodies[ix(i)];
        const double acc = c_a * (u[ix(i)] - un_[ix(i)]) - 2.0 * c_v * vn_[ix(i)] - a_[ix(i)];
        res_[ix(i)] = b.m * acc + b.c * v[ix(i)] + b.k * u[ix(i)] + b.m * ag - f_[ix(i)];
        diag_[ix(i)] = c_a * b.m + c_v * b.c + b.k;
        upper_[ix(i)] = 0.0;
        scale = std::max(scale, std::abs(u[ix(i)]));
      }
      for (int j = 0; j < nc_; ++j) {
        if (!closed_[ix(j)]) continue;
        double dp = 0.0, dq = 0.0;
        el_.law(j).slopes(el_.p(j, u.data()), el_.q(j, v.data()), vm_[ix(j)], dp, dq);
        const double kappa = dp + c_v * dq;
        const int r = sys_.right(j), l = sys_.left(j);
        diag_[ix(r)] += kappa;
        if (l != kWall) {
          diag_[ix(l)] += kappa;
          upper_[ix(l)] -= kappa;  // (l, l + 1) and (l + 1, l): contacts join neighbours
        }
      }
      if (!solve_tridiagonal()) break;
      double largest = 0.0;
      for (int i = 0; i < n_; ++i) {
        u[ix(i)] -= du_[ix(i)];
        largest = std::max(largest, std::abs(du_[ix(i)]));
      }
      converged = largest <= kNewtonTolerance * scale;
    }
    if (!converged) {
      u = un_;
      v = vn_;
      res.status = Status::failed;
      res.message = "Newton's iteration on the contact forces did not converge in " +
                    std::to_string(kNewtonIterations) + " iterations at t = " + std::to_string(t1) +
                    " (a step too large for the contact stiffness)";
      return StepOutcome::refused;
    }
    for (int i = 0; i < n_; ++i) {
      v[ix(i)] = c_v * (u[ix(i)] - un_[ix(i)]) - vn_[ix(i)];
      a_[ix(i)] = c_a * (u[ix(i)] - un_[ix(i)]) - 2.0 * c_v * vn_[ix(i)] - a_[ix(i)];
    }
    forces(u, v);  // the closed set at the converged state
    for (int j = 0; j < nc_; ++j) {
      const bool now = closed_[ix(j)] != 0, before = el_.closed(j);
      out_.entered[ix(j)] = now && !before;
      if (now && !before) el_.close(j, el_.q(j, vn_.data()));
      if (!now && before) el_.open(j, el_.q(j, v.data()));
      out_.force[ix(j)] = now ? el_.law(j).force(el_.p(j, u.data()), el_.q(j, v.data()), vm_[ix(j)]) : 0.0;
    }
    return StepOutcome::taken;
  }

  void finish(Result& res) override {
    res.impacts = el_.impacts();
    res.contact_phases = 0;
    el_.finish(res);  // restitution over whole contacts, not over one step
  }

 private:
  // The approach rate each contact's element takes: its own if closed, else the rate at the
  // step's start (out_.v), should it close in the step.
  void onset_rates() {
    for (int j = 0; j < nc_; ++j)
      vm_[ix(j)] = el_.closed(j) ? el_.v_minus(j) : el_.onset_rate(el_.q(j, out_.v.data()));
  }

  // The element forces on the bodies at (u, v), closing the elements whose penetration is
  // positive there.
  void forces(const std::vector<double>& u, const std::vector<double>& v) {
    std::fill(f_.begin(), f_.end(), 0.0);
    for (int j = 0; j < nc_; ++j) {
      const double p = el_.p(j, u.data());
      closed_[ix(j)] = p > 0.0;
      if (!closed_[ix(j)]) continue;
      const double F = el_.law(j).force(p, el_.q(j, v.data()), vm_[ix(j)]);
      f_[ix(sys_.right(j))] += F;
      if (sys_.left(j) != kWall) f_[ix(sys_.left(j))] -= F;
    }
  }

  // du = J^-1 res, J symmetric tridiagonal (diag_, upper_); false if a pivot vanished.
  bool solve_tridiagonal() {
    for (int i = 1; i < n_; ++i) {
      const double w = upper_[ix(i - 1)] / diag_[ix(i - 1)];
      diag_[ix(i)] -= w * upper_[ix(i - 1)];
      res_[ix(i)] -= w * res_[ix(i - 1)];
    }
    for (int i = n_; i-- > 0;) {
      if (!(std::abs(diag_[ix(i)]) > 0.0)) return false;
      const double rhs = res_[ix(i)] - (i + 1 < n_ ? upper_[ix(i)] * du_[ix(i + 1)] : 0.0);
      du_[ix(i)] = rhs / diag_[ix(i)];
    }
    return true;
  }

  const System& sys_;
  LoadCursor load_;  // a_g at each step's end, O(1) on a record
  Elements& el_;
  double h_;
  int n_, nc_;
  std::vector<double> a_, un_, vn_, res_, diag_, upper_, du_, f_, vm_;
  std::vector<char> closed_;
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
