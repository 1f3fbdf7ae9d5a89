#include "solvers/moreau_jean/yielding.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "kit/fixed_step.hpp"
#include "solvers/moreau_jean/dynamic.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "kit/run_limits.hpp"

namespace pb::moreau_jean {

namespace {

// Branch iterations a step may take before the run fails: each changes at least one body's
// branch, and the monotone step equation settles in about one change per body (two where a
// body goes from one limit to the other in a step). The cap guards against cycling; no run
// of cases/sets/yielding.toml reaches it (all 6 242 end ok at the default N).
int max_passes(int nb) { return 2 * nb + 4; }

// A yielding body's constants and state, per slot (slot 0: the wall or the unused slot,
// and elastic bodies: u_y infinite, never off their elastic branch).
struct Plastic {
  double theta = 0.5, h = 0.0, alpha = 0.0;
  Eigen::VectorXd m, c, k, u_y;
  Eigen::VectorXd z;        // the hysteretic variable (an elastic body's: its u)
  std::vector<int> branch;  // 0 elastic, +-1 yielding at z = +-u_y
  std::vector<int> body;    // the slots of yielding bodies
  // The contact flags before a step, restored for each further pass of its iteration.
  std::vector<char> active, pushed, in_phase;
  double input = 0.0;       // the ground's work on every body
  double hysteretic = 0.0;  // what body ref's hysteresis dissipated
};

Plastic make_plastic(const System& s, double h, double theta, const dynamic::State& st) {
  Plastic p;
  p.theta = theta;
  p.h = h;
  p.alpha = s.alpha;
  const Eigen::Index slots = s.n_bodies() + 1;
  for (Eigen::VectorXd* x : {&p.m, &p.c, &p.k}) x->setZero(slots);
  p.u_y.setConstant(slots, std::numeric_limits<double>::infinity());
  for (int i = 0; i < s.n_bodies(); ++i) {
    const Body& b = s.bodies[static_cast<std::size_t>(i)];
    p.m(i + 1) = b.m;
    p.c(i + 1) = b.c;
    p.k(i + 1) = b.k;
    p.u_y(i + 1) = b.u_y;
    if (b.yields()) p.body.push_back(i + 1);
  }
  p.z = st.q;  // at rest with z = 0, and an elastic body's z is its u
  p.branch.assign(static_cast<std::size_t>(slots), 0);
  p.active = st.active;
  p.pushed = st.pushed;
  p.in_phase = st.in_phase;
  return p;
}

// Slot x's coefficients on its branch (stepper.hpp's, with K_b and the constant force f0 of
// the branch: M_hat = m + h theta c + h^2 theta^2 K_b), into the scheme, and its contacts'
// entries of W^T M_hat^-1 W.
void set_branch(const Plastic& p, dynamic::Scheme& sc, int x) {
  const double h = p.h, theta = p.theta;
  const double kb = p.branch[static_cast<std::size_t>(x)] == 0 ? p.k(x) : p.alpha * p.k(x);
  const double m_hat = p.m(x) + h * theta * p.c(x) + h * h * theta * theta * kb;
  sc.minv(x) = 1.0 / m_hat;
  sc.h_minv(x) = h * theta * sc.minv(x);
  for (int j : {x - 1 - sc.first, x - sc.first}) {  // the contacts left and right of slot x
    if (j < 0 || j >= sc.nc) continue;
    const int l = sc.first + j, r = l + 1;
    sc.diag(j) = sc.minv(l) + sc.minv(r);
    sc.off(j) = -sc.minv(r);
  }
}

// The free motion of slot x over the step from (q, v) under abar, on its branch:
//   M_hat dv = h (-c v - theta (K_b (q + h v) + f0) - (1 - theta) r_k - m abar),
//   v_free = v + dv,  q_free = q + h v + h theta dv.
void free_motion(const Plastic& p, const dynamic::Scheme& sc, const dynamic::State& st, dynamic::Work& w, int x,
                 double abar) {
  const double h = p.h, theta = p.theta, q = st.q(x), v = st.v(x), k = p.k(x), z = p.z(x);
  const int s = p.branch[static_cast<std::size_t>(x)];
  const double plastic = (1.0 - p.alpha) * k;
  const double r_k = p.alpha * k * q + plastic * z;
  // elastic: k q_k+1 - (1 - alpha) k (q_k - z_k); yielding: alpha k q_k+1 + (1 - alpha) k s u_y
  const double kb = s == 0 ? k : p.alpha * k;
  const double f0 = s == 0 ? -plastic * (q - z) : plastic * s * p.u_y(x);
  const double force = -p.c(x) * v - theta * (kb * (q + h * v) + f0) - (1.0 - theta) * r_k - p.m(x) * abar;
  const double dv = sc.minv(x) * h * force;
  w.v_new(x) = v + dv;
  w.q_new(x) = q + h * v + h * theta * dv;
}

// Each yielding body's branch where its return map puts q_k+1 (in w.q_new); true if one
// changed.
bool rebranch(Plastic& p, dynamic::Scheme& sc, const dynamic::State& st, const dynamic::Work& w) {
  bool changed = false;
  for (int x : p.body) {
    const double trial = p.z(x) + (w.q_new(x) - st.q(x));
    int& s = p.branch[static_cast<std::size_t>(x)];
    const int want = trial > p.u_y(x) ? 1 : trial < -p.u_y(x) ? -1 : 0;
    // A yielding body stays on its branch while its trial is at or beyond its limit.
    if (want == s || (s != 0 && s * trial >= p.u_y(x))) continue;
    s = want;
    set_branch(p, sc, x);
    changed = true;
  }
  return changed;
}

// One step: branches, free motion and contacts until the branches hold; then z by the
// return map, the dissipation and the ground's work. False: the run blew up, or (message
// set) the branches never settled.
bool step(Plastic& p, dynamic::Scheme& sc, dynamic::State& st, dynamic::Work& w, Tally& t, double abar,
          std::vector<double>* history, std::string& message) {
  const Tally before = t;
  std::copy(st.active.begin(), st.active.end(), p.active.begin());
  std::copy(st.pushed.begin(), st.pushed.end(), p.pushed.begin());
  std::copy(st.in_phase.begin(), st.in_phase.end(), p.in_phase.begin());
  for (int pass = 0;; ++pass) {
    for (int x = 1; x <= sc.nb; ++x) free_motion(p, sc, st, w, x, abar);
    dynamic::contacts(sc, st, w, t);
    if (!rebranch(p, sc, st, w)) break;
    if (pass + 1 == max_passes(sc.nb)) {
      message = "yield: the return map's branches did not settle at t = " +
                std::to_string(static_cast<double>(st.k) * sc.h);
      return false;
    }
    t = before;
    std::copy(p.active.begin(), p.active.end(), st.active.begin());
    std::copy(p.pushed.begin(), p.pushed.end(), st.pushed.begin());
    std::copy(p.in_phase.begin(), p.in_phase.end(), st.in_phase.begin());
  }
  for (int x = 1; x <= sc.nb; ++x) {
    const double dq = w.q_new(x) - st.q(x);
    p.input -= p.m(x) * abar * dq;  // the step mean of the load times the step's travel
    const double trial = p.z(x) + dq, z_new = std::clamp(trial, -p.u_y(x), p.u_y(x));
    // (1 - alpha) k z de with de = trial - z_k+1 the plastic travel the map removed (zero,
    // exactly, on the elastic branch), at z_k+1 = +-u_y: the implicit step's dissipation.
    if (x == sc.ref) p.hysteretic += (1.0 - p.alpha) * p.k(x) * z_new * (trial - z_new);
    p.z(x) = z_new;
  }
  return dynamic::finish_step(sc, st, w, t, history);
}

}  // namespace

Result run_yielding(const System& sys, const Settings& set, double h, long n, Result res) {
  dynamic::Scheme sc = dynamic::make_scheme(sys, h, set.theta, set.gamma, set.variant == kEndSamples
                                                                               ? LoadRule::end_samples
                                                                               : LoadRule::step_mean);
  dynamic::Work work = dynamic::make_work(sc);
  Tally tally;
  std::vector<double>* rows = set.history_samples > 0 ? &res.history.data : nullptr;
  dynamic::State st = dynamic::start_run(sc, sys, n, work, tally, res, rows);
  Plastic p = make_plastic(sys, h, set.theta, st);
  for (int x = 1; x <= sc.nb; ++x) set_branch(p, sc, x);
  Deadline deadline(set);
  std::string why;
  bool finite = true;
  constexpr long kChunk = 1L << 14;
  while (finite && st.k < n) {
    finite = drive(sc.load, st.k, std::min(n, st.k + kChunk), [&](double abar, double) {
      return step(p, sc, st, work, tally, abar, rows, why);
    });
    if (finite && st.k < n && deadline.passed(st.k)) {
      res.status = Status::time_limit;
      res.message = deadline.reason() + " at t = " + std::to_string(static_cast<double>(st.k) * h);
      break;
    }
  }
  if (!why.empty()) {
    res.status = Status::failed;
    res.message = why;
  } else if (!finite) {
    res.status = st.q.allFinite() && st.v.allFinite() ? Status::diverged : Status::nan;
  }
  finish_steps(sys, tally, st.k, h, nullptr, res);
  res.residual = sys.residual(st.q(sc.ref), p.z(sc.ref));
  res.hysteretic = p.hysteretic / p.input;
  return res;
}

}  // namespace pb::moreau_jean
