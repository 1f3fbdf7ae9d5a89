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
//
// The Kelvin-Voigt force jumps by c q where the penetration turns positive (and where it
// ends, the dashpot pulling): a step whose end lies at that jump has no solution, and
// Newton's iterates flip the element open and closed without end (at K = 1e4, N = 64, 130 of
// the 224 work-precision runs failed so). The force law there is set-valued, F in
// [min(0, c q), max(0, c q)] at p = 0 (its convex hull, Filippov's), and that equation has a
// solution: an element whose state flips twice in one step is pinned, its gap held at zero at
// the step's end by a force lambda, solved with the step. lambda outside that interval
// means the element is closed (or open) after all, and it is released to that state. An
// element pinned at the step's end starts (or ends) its contact there. Elements whose force is
// continuous at p = 0 (the Hertz family) never flip so.
//
// Where the load jumps (load_jumps below), a step is split at the jump, and the step after it
// starts from the acceleration of the load after it: second order across it.
//
// A yielding body's spring is the bilinear law's return map at the iterate (hysteresis.hpp):
// its force and its slope, k or alpha k, enter R and the Jacobian as OpenSees' Newton runs a
// Steel01 material with hardening; the step's end commits its z.

#include <cmath>
#include <string>
#include <vector>

#include "solvers/compliant/integrators.hpp"
#include "solvers/contact_elements/elements.hpp"
#include "solvers/fixed_step.hpp"
#include "solvers/hysteresis.hpp"

namespace pb::compliant {

namespace {

// Iterations before a step is given up, and the correction (over a_p / w_p^2 plus the
// largest |u|) below which an iterate counts as converged.
constexpr int kNewtonIterations = 50;
constexpr double kNewtonTolerance = 1e-13;

// Where the load jumps, and its values just before and after: the end of every load (the
// paper's cosine pulse ends at s a_p, a record at its last sample), and a record's first
// sample when it comes after t = 0 (at t = 0 the start's acceleration is the load's there
// already). The trapezoidal rule is second order for a smooth load and across a kink (a
// record's samples: one kink per sample whatever the step, each an O(h^3) error), but a
// jump it integrates to O(h), and an acceleration carried across it from the load before
// was an O(h) error in every later velocity: the cosine pulse's Pi1 erred 6.6e-4, 1.6e-4,
// 4.1e-5 at N = 1024, 4096, 16384 (the sine's, continuous, 4.6e-6, 2.7e-7, 1.7e-8).
struct LoadJump {
  double t, before, after;
};

std::vector<LoadJump> load_jumps(const Pulse& p) {
  std::vector<LoadJump> jumps;
  if (p.record && p.record->t.front() > 0.0)
    jumps.push_back({p.record->t.front(), 0.0, p.accel(p.record->t.front())});
  const double end = p.duration();
  jumps.push_back({end, p.accel(end), 0.0});
  std::erase_if(jumps, [](const LoadJump& j) { return j.before == j.after; });
  return jumps;
}

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
    mult_.assign(nb, 0.0);
    pinned_.assign(ix(nc_), 0);
    flips_.assign(ix(nc_), 0);
    last_.assign(ix(nc_), -1);
    decided_.assign(ix(nc_), -1);
    pin_index_.assign(ix(nc_), 0);
    lambda_.assign(ix(nc_), 0.0);
    w_.assign(nb, 0.0);
    rhs_.assign(ix(nc_), 0.0);
    s_.assign(ix(nc_ * nc_), 0.0);
    z_.assign(ix(nc_), std::vector<double>(nb, 0.0));
    start_u_ = out_.u;
    start_v_ = out_.v;
    jumps_ = load_jumps(sys.pulse);
    // As LoadCursor::sample treats the load's end: within 1e-9 max(h, T) of a step's end, a
    // jump is at that end (so that T_p = N h ends the pulse on a boundary however N h rounds).
    for (const LoadJump& j : jumps_) jump_tol_ = std::max(jump_tol_, 1e-9 * std::max(h, j.t));
    zn_ = out_.u;  // z = u: at rest a yielding body's z is 0, and an elastic body's is its u
    onset_rates();
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
    pinned_now_ = false;
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
    if (pinned_now_) ++pinned_steps_;
    return StepOutcome::taken;
  }

  // One Newmark step of length h ending at t1 under the load ag there (out_ from the step's
  // start to its end); false, with res saying why, when Newton's iteration fails.
  bool advance(double h, double t1, double ag, Result& res) {
    std::vector<double>& u = out_.u;
    std::vector<double>& v = out_.v;
    un_ = u;
    vn_ = v;
    onset_rates();
    const double c_a = 4.0 / (h * h), c_v = 2.0 / h;
    // Predictor: constant acceleration.
    for (int i = 0; i < n_; ++i) u[ix(i)] = un_[ix(i)] + h * vn_[ix(i)] + 0.25 * h * h * a_[ix(i)];
    bool converged = false;
    std::fill(flips_.begin(), flips_.end(), 0);
    std::fill(pinned_.begin(), pinned_.end(), 0);
    std::fill(last_.begin(), last_.end(), -1);
    std::fill(decided_.begin(), decided_.end(), -1);
    pins_ = 0;
    for (int it = 0; it < kNewtonIterations && !converged; ++it) {
      for (int i = 0; i < n_; ++i) v[ix(i)] = c_v * (u[ix(i)] - un_[ix(i)]) - vn_[ix(i)];
      forces(u, v);
      count_flips();
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
      for (int j = 0; j < nc_; ++j) {
        if (!closed_[ix(j)] || pinned_[ix(j)]) continue;
        double dp = 0.0, dq = 0.0;
        el_.law(j).slopes(el_.p(j, u.data()), el_.q(j, v.data()), vm_[ix(j)], dp, dq);
        if (decided_[ix(j)] == 1 && el_.law(j).model == Model::kelvin_voigt) dp = el_.law(j).k, dq = el_.law(j).c;
        const double kappa = dp + c_v * dq;
        const int r = sys_.right(j), l = sys_.left(j);
        diag_[ix(r)] += kappa;
        if (l != kWall) {
          diag_[ix(l)] += kappa;
          upper_[ix(l)] -= kappa;  // (l, l + 1) and (l + 1, l): contacts join neighbours
        }
      }
      if (!solve_pinned(u)) break;
      double largest = 0.0;
      for (int i = 0; i < n_; ++i) {
        u[ix(i)] -= du_[ix(i)];
        largest = std::max(largest, std::abs(du_[ix(i)]));
      }
      converged = largest <= kNewtonTolerance * scale;
      if (converged) {  // a pin whose force left its interval goes back to open or closed
        for (int i = 0; i < n_; ++i) v[ix(i)] = c_v * (u[ix(i)] - un_[ix(i)]) - vn_[ix(i)];
        converged = release_pins(v);
      }
    }
    if (!converged) {
      res.status = Status::failed;
      res.message = "Newton's iteration on the contact forces did not converge in " +
                    std::to_string(kNewtonIterations) + " iterations at t = " + std::to_string(t1) +
                    " (a step too large for the contact stiffness)";
      return false;
    }
    for (int i = 0; i < n_; ++i) {
      v[ix(i)] = c_v * (u[ix(i)] - un_[ix(i)]) - vn_[ix(i)];
      a_[ix(i)] = c_a * (u[ix(i)] - un_[ix(i)]) - 2.0 * c_v * vn_[ix(i)] - a_[ix(i)];
    }
    if (sys_.yields()) {
      for (int i = 0; i < n_; ++i) {
        const double du = u[ix(i)] - un_[ix(i)];
        const Hysteresis spring = return_map(sys_.bodies[ix(i)], sys_.alpha, zn_[ix(i)], u[ix(i)], du);
        yield_tally_.step(sys_, i, 0.5 * (ag_n_ + ag), du, spring);  // the load's trapezoid
        zn_[ix(i)] = spring.z;
      }
    }
    ag_n_ = ag;
    forces(u, v);  // the closed set at the converged state; a pinned gap is closed while approaching
    for (int j = 0; j < nc_; ++j) {
      if (pinned_[ix(j)]) closed_[ix(j)] = el_.q(j, v.data()) > 0.0;
      const bool now = closed_[ix(j)] != 0, before = el_.closed(j);
      if (now && !before) {
        out_.entered[ix(j)] = 1;
        el_.close(j, el_.q(j, vn_.data()), t1);
      }
      if (!now && before) el_.open(j, el_.q(j, v.data()));
      out_.force[ix(j)] = pinned_[ix(j)] ? lambda_[ix(j)]
                          : now ? el_.law(j).force(el_.p(j, u.data()), el_.q(j, v.data()), vm_[ix(j)])
                                : 0.0;
    }
    if (pins_ > 0) pinned_now_ = true;
    return true;
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
    if (pinned_steps_ > 0 && res.status == Status::ok)
      res.message = std::to_string(pinned_steps_) + " steps ended with a gap pinned at zero (set-valued onset)";
  }

 private:
  // The approach rate each contact's element takes: its own if closed, else the rate at the
  // step's start (out_.v), should it close in the step.
  void onset_rates() {
    for (int j = 0; j < nc_; ++j)
      vm_[ix(j)] = el_.closed(j) ? el_.v_minus(j) : el_.onset_rate(el_.q(j, out_.v.data()));
  }

  // The element forces on the bodies at (u, v), closing the elements whose penetration is
  // positive there; a pinned element's force is its unknown lambda (solve_pinned).
  void forces(const std::vector<double>& u, const std::vector<double>& v) {
    std::fill(f_.begin(), f_.end(), 0.0);
    for (int j = 0; j < nc_; ++j) {
      const double p = el_.p(j, u.data());
      if (pinned_[ix(j)]) continue;
      closed_[ix(j)] = decided_[ix(j)] >= 0 ? decided_[ix(j)] == 1 : p > 0.0;
      if (!closed_[ix(j)]) continue;
      const Law& law = el_.law(j);
      // An element released closed from a pin keeps its linear law through p = 0 in this step.
      const double F = decided_[ix(j)] == 1 && law.model == Model::kelvin_voigt
                           ? law.k * p + law.c * el_.q(j, v.data())
                           : law.force(p, el_.q(j, v.data()), vm_[ix(j)]);
      f_[ix(sys_.right(j))] += F;
      if (sys_.left(j) != kWall) f_[ix(sys_.left(j))] -= F;
    }
  }

  // Counts each unpinned element's changes of state in this step's iterations, and pins one at
  // its second (one released from a pin keeps the state it was released to).
  void count_flips() {
    for (int j = 0; j < nc_; ++j) {
      if (pinned_[ix(j)] || decided_[ix(j)] >= 0) continue;
      const int state = closed_[ix(j)];
      if (last_[ix(j)] >= 0 && state != last_[ix(j)] && ++flips_[ix(j)] >= 2) {
        pinned_[ix(j)] = 1;
        lambda_[ix(j)] = 0.0;
        ++pins_;
      }
      last_[ix(j)] = state;
    }
  }

  // Releases every pin whose force left [min(0, c q), max(0, c q)] at rates v: above it the
  // element is closed, below it open, for the rest of the step. True when none was released.
  bool release_pins(const std::vector<double>& v) {
    bool kept = true;
    for (int j = 0; j < nc_; ++j) {
      if (!pinned_[ix(j)]) continue;
      const double cq = el_.law(j).c * el_.q(j, v.data()), lo = std::min(0.0, cq), hi = std::max(0.0, cq);
      const double slack = 1e-12 * (std::abs(cq) + std::abs(lambda_[ix(j)]));
      if (lambda_[ix(j)] >= lo - slack && lambda_[ix(j)] <= hi + slack) continue;
      pinned_[ix(j)] = 0;
      --pins_;
      decided_[ix(j)] = lambda_[ix(j)] > hi ? 1 : 0;
      kept = false;
    }
    return kept;
  }

  // du from J du = res with every pinned gap held at zero at u - du by its force lambda:
  // J du = res - W lambda_new + ... solved as du = z - sum_k Z_k lambda_k, z = J^-1 res,
  // Z_k = J^-1 W_k, with S lambda = W^T z - g(u), S_jk = W_j^T Z_k (a pinned element's own
  // force is its unknown; res holds the others'). False if a pivot vanished.
  bool solve_pinned(const std::vector<double>& u) {
    if (!factor_tridiagonal()) return false;
    // res as assembled holds -lambda_old W (forces() left pinned forces out): the unknown is
    // lambda itself.
    solve_factored(res_, du_);
    if (pins_ == 0) return true;
    int m = 0;
    for (int j = 0; j < nc_; ++j)
      if (pinned_[ix(j)]) pin_index_[ix(m++)] = j;
    for (int a = 0; a < m; ++a) {
      const int j = pin_index_[ix(a)];
      std::fill(w_.begin(), w_.end(), 0.0);
      w_[ix(sys_.right(j))] = 1.0;
      if (sys_.left(j) != kWall) w_[ix(sys_.left(j))] = -1.0;
      solve_factored(w_, z_[ix(a)]);
    }
    const auto wdot = [&](int j, const std::vector<double>& x) {
      return x[ix(sys_.right(j))] - (sys_.left(j) != kWall ? x[ix(sys_.left(j))] : 0.0);
    };
    for (int a = 0; a < m; ++a) {
      const int j = pin_index_[ix(a)];
      rhs_[ix(a)] = wdot(j, du_) - sys_.gap(j, u.data());
      for (int b = 0; b < m; ++b) s_[ix(a * m + b)] = wdot(j, z_[ix(b)]);
    }
    if (!solve_dense(m)) return false;
    for (int a = 0; a < m; ++a) {
      const int j = pin_index_[ix(a)];
      lambda_[ix(j)] = rhs_[ix(a)];
      for (int i = 0; i < n_; ++i) du_[ix(i)] -= z_[ix(a)][ix(i)] * lambda_[ix(j)];
    }
    return true;
  }

  // Gaussian elimination with partial pivoting on s_ (m x m, m the pins), rhs_ in place.
  bool solve_dense(int m) {
    for (int c = 0; c < m; ++c) {
      int piv = c;
      for (int r = c + 1; r < m; ++r)
        if (std::abs(s_[ix(r * m + c)]) > std::abs(s_[ix(piv * m + c)])) piv = r;
      if (!(std::abs(s_[ix(piv * m + c)]) > 0.0)) return false;
      for (int k = 0; k < m; ++k) std::swap(s_[ix(c * m + k)], s_[ix(piv * m + k)]);
      std::swap(rhs_[ix(c)], rhs_[ix(piv)]);
      for (int r = c + 1; r < m; ++r) {
        const double f = s_[ix(r * m + c)] / s_[ix(c * m + c)];
        for (int k = c; k < m; ++k) s_[ix(r * m + k)] -= f * s_[ix(c * m + k)];
        rhs_[ix(r)] -= f * rhs_[ix(c)];
      }
    }
    for (int r = m; r-- > 0;) {
      double x = rhs_[ix(r)];
      for (int k = r + 1; k < m; ++k) x -= s_[ix(r * m + k)] * rhs_[ix(k)];
      rhs_[ix(r)] = x / s_[ix(r * m + r)];
    }
    return true;
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
  std::vector<double> a_, un_, vn_, res_, diag_, upper_, mult_, du_, f_, vm_;
  std::vector<char> closed_;
  // Pins of this step (the set-valued onset), and what solving with them needs.
  std::vector<char> pinned_;
  std::vector<int> flips_, last_, decided_, pin_index_;
  std::vector<double> lambda_, w_, rhs_, s_;
  std::vector<std::vector<double>> z_;
  int pins_ = 0;
  long pinned_steps_ = 0;
  bool pinned_now_ = false;  // a pin in this step (in either part of a split one)
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
