#include "solvers/moreau_jean/dynamic.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "kit/lcp/small.hpp"

namespace pb::moreau_jean::dynamic {

Scheme make_scheme(const System& s, double h, double theta, double gamma, LoadRule load) {
  Scheme sc;
  sc.nb = s.n_bodies();
  sc.nc = s.n_contacts();
  sc.first = s.wall ? 0 : 1;
  sc.ref = s.ref + 1;
  sc.h = h;
  sc.gamma_h = gamma * h;
  sc.eps = s.eps;
  sc.delta = s.delta;
  sc.bound = 1e6 * s.length_scale();
  const double h_old = h * (1.0 - theta), h_new = h * theta;
  const Eigen::Index slots = sc.nb + 1;
  for (Eigen::VectorXd* x : {&sc.fv, &sc.fq, &sc.fa, &sc.qv, &sc.qq, &sc.qa, &sc.minv, &sc.h_minv})
    x->setZero(slots);  // slot 0 keeps zeros: the wall (or the unused slot) never moves
  // The same expressions, in the same order, as make_scheme in stepper.hpp: the two paths
  // agree to the last bit where their sums agree.
  for (int i = 0; i < sc.nb; ++i) {
    const Body& b = s.bodies[static_cast<std::size_t>(i)];
    const Eigen::Index x = i + 1;
    const double m_hat = b.m + h * theta * b.c + h * h * theta * theta * b.k;
    sc.minv(x) = 1.0 / m_hat;
    sc.h_minv(x) = h_new * sc.minv(x);
    sc.fv(x) = 1.0 - h * (b.c + h * theta * b.k) / m_hat;
    sc.fq(x) = -h * b.k / m_hat;
    sc.fa(x) = -h * b.m / m_hat;
    sc.qv(x) = h_old + h_new * sc.fv(x);
    sc.qq(x) = 1.0 + h_new * sc.fq(x);
    sc.qa(x) = h_new * sc.fa(x);
  }
  sc.diag.setZero(sc.nc);
  sc.off.setZero(sc.nc);
  for (int j = 0; j < sc.nc; ++j) {
    const int l = sc.first + j, r = l + 1;
    sc.diag(j) = sc.minv(l) + sc.minv(r);
    sc.off(j) = -sc.minv(r);  // the right body of j is the left body of j + 1
  }
  sc.load = make_pulse_load(s.pulse, h, load, theta);
  return sc;
}

State make_state(const Scheme& sc, const double* u, const double* v) {
  State st;
  st.q.setZero(sc.nb + 1);
  st.v.setZero(sc.nb + 1);
  for (int i = 0; i < sc.nb; ++i) {
    st.q(i + 1) = u[i];
    st.v(i + 1) = v[i];
  }
  st.g.resize(sc.nc);
  st.rate.resize(sc.nc);
  for (int j = 0; j < sc.nc; ++j) {
    const int l = sc.first + j, r = l + 1;
    st.g(j) = sc.delta + (st.q(r) - st.q(l));
    st.rate(j) = st.v(r) - st.v(l);
  }
  const auto nc = static_cast<std::size_t>(sc.nc);
  st.active.assign(nc, 0);
  st.pushed.assign(nc, 0);
  st.in_phase.assign(nc, 0);
  return st;
}

Work make_work(const Scheme& sc) {
  Work w;
  w.v_new.setZero(sc.nb + 1);
  w.q_new.setZero(sc.nb + 1);
  w.rhs.setZero(sc.nc);
  w.impulse.setZero(sc.nc);
  w.lcp.reserve(sc.nc);
  return w;
}

State start_run(const Scheme& sc, const System& sys, long n, const Work& w, Tally& tally, Result& res,
                std::vector<double>* rows) {
  std::vector<double> u0(static_cast<std::size_t>(sc.nb), 0.0), v0(u0.size(), 0.0);
  if (!sys.u_start.empty()) u0.assign(sys.u_start.begin(), sys.u_start.end());
  if (!sys.v_start.empty()) v0.assign(sys.v_start.begin(), sys.v_start.end());
  State st = make_state(sc, u0.data(), v0.data());
  tally.u_max = std::abs(st.q(sc.ref));
  if (sc.nc > 0) tally.g_min = std::min(0.0, st.g.minCoeff());
  if (rows) {
    res.history.n_bodies = sc.nb;
    res.history.n_contacts = sc.nc;
    rows->reserve(static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(res.history.row_size()));
    record(sc, st, w.impulse, *rows);
  }
  return st;
}

void record(const Scheme& sc, const State& st, const Eigen::VectorXd& impulse, std::vector<double>& out) {
  out.push_back(static_cast<double>(st.k) * sc.h);
  for (int i = 1; i <= sc.nb; ++i) out.push_back(st.q(i));
  for (int i = 1; i <= sc.nb; ++i) out.push_back(st.v(i));
  for (int j = 0; j < sc.nc; ++j) out.push_back(st.g(j));
  for (int j = 0; j < sc.nc; ++j) out.push_back(impulse(j) / sc.h);
}

namespace {

// Newton's law on the run of active contacts [a, a + n), and its impulses applied to the
// run's n + 1 bodies.
void solve_run(const Scheme& sc, const State& st, Work& w, int a, int n) {
  double* v_new = w.v_new.data();
  double* q_new = w.q_new.data();
  double* rhs = w.rhs.data();
  double* p = w.impulse.data();
  for (int j = a; j < a + n; ++j) {
    const int l = sc.first + j;
    rhs[j] = (v_new[l + 1] - v_new[l]) + sc.eps * st.rate(j);
  }
  if (n == 1) {
    p[a] = lcp::solve1(sc.diag(a), rhs[a]);
  } else if (n == 2) {
    Eigen::Matrix2d m;
    m << sc.diag(a), sc.off(a), sc.off(a), sc.diag(a + 1);
    const Eigen::Vector2d z = lcp::solve2(m, Eigen::Vector2d(rhs[a], rhs[a + 1]));
    p[a] = z(0);
    p[a + 1] = z(1);
  } else {
    w.lcp_passes += w.lcp.solve(sc.diag.data() + a, sc.off.data() + a, rhs + a, p + a, n, st.pushed.data() + a);
  }
  // Body x of the run takes +P of the contact on its left and -P of the one on its right,
  // summed before it is added, as the fixed-size path's M_hat^-1 W P does.
  for (int m = 0; m <= n; ++m) {
    const int x = sc.first + a + m;
    const double from_left = m > 0 ? p[a + m - 1] : 0.0, from_right = m < n ? p[a + m] : 0.0;
    v_new[x] += sc.minv(x) * from_left - sc.minv(x) * from_right;
    q_new[x] += sc.h_minv(x) * from_left - sc.h_minv(x) * from_right;
  }
}

// The contacts of a step, on the free motion in w.v_new, w.q_new: one scan over the
// contacts finds the index set, solves each run of consecutive active contacts where it
// ends, and updates the counts and flags. (Values the scan reads are copied to locals: a
// store through a char pointer may alias anything, and would make the compiler reload
// them at every contact.)
[[gnu::always_inline]] inline void contacts_of_step(const Scheme& sc, State& st, Work& w, Tally& t) {
  const int nc = sc.nc;
  const double* g = st.g.data();
  double* rate = st.rate.data();
  w.impulse.setZero();
  const double gamma_h = sc.gamma_h;
  const double* p = w.impulse.data();
  char* was_active = st.active.data();
  char* pushed = st.pushed.data();
  char* in_phase = st.in_phase.data();
  long phases = 0;
  int j = 0;
  while (j < nc) {
    if (g[j] + gamma_h * rate[j] > 0.0) {
      // Open now: nothing to count, and the flags to clear (in_phase implies pushed).
      if (was_active[j] | pushed[j]) was_active[j] = pushed[j] = in_phase[j] = 0;
      ++j;
      continue;
    }
    const int a = j;
    while (++j < nc && g[j] + gamma_h * rate[j] <= 0.0) {
    }
    solve_run(sc, st, w, a, j - a);  // reads the flags of the step before: updated below
    for (int i = a; i < j; ++i) {
      const int pushing = p[i] > 0.0;
      if (!was_active[i] & (rate[i] < 0.0)) t.impact(static_cast<double>(st.k + 1) * sc.h, rate[i]);
      const int starts = pushing & pushed[i] & !in_phase[i];
      phases += starts;
      in_phase[i] = static_cast<char>((in_phase[i] | starts) & pushing);
      pushed[i] = static_cast<char>(pushing);
      was_active[i] = 1;
    }
  }
  t.phases += phases;
}

// The step's end once v_new, q_new hold the new state: the state moves there, its gaps and
// rates, the monitor, divergence, the tally and the history row.
[[gnu::always_inline]] inline bool end_of_step(const Scheme& sc, State& st, Work& w, Tally& t, double work,
                                               std::vector<double>* history, StepMonitor* monitor) {
  const int nc = sc.nc;
  st.q.swap(w.q_new);
  st.v.swap(w.v_new);
  ++st.k;
  // The gaps and rates of the new state, as differences of shifted segments (vectorised).
  st.g.array() = sc.delta + (st.q.segment(sc.first + 1, nc) - st.q.segment(sc.first, nc)).array();
  st.rate = st.v.segment(sc.first + 1, nc) - st.v.segment(sc.first, nc);
  // Before the divergence test: a diverging run's energy excess shows the growth.
  if (monitor) monitor->step(sc.h, work, st.q.data() + 1, st.v.data() + 1, st.pushed.data());
  // Both vectorise; a NaN anywhere makes the sum NaN, whatever maxCoeff makes of it.
  const auto u = st.q.tail(sc.nb);
  if (!(u.cwiseAbs().maxCoeff() <= sc.bound) || std::isnan(u.sum())) return false;
  // Not in the contact scan: a running minimum there is a chain of dependent operations.
  if (nc > 0) t.g_min = std::min(t.g_min, st.g.minCoeff());
  const double u_ref = std::abs(st.q(sc.ref));
  if (u_ref > t.u_max) {
    t.u_max = u_ref;
    t.k_max = st.k;
  }
  if (history) record(sc, st, w.impulse, *history);
  return true;
}

// One step from st.k to st.k + 1 under the ground load abar (work: the exact step mean, for
// the monitor); false when the state is no longer finite or |u| passed the divergence bound.
bool step(const Scheme& sc, State& st, Work& w, Tally& t, double abar, double work, std::vector<double>* history,
          StepMonitor* monitor) {
  w.v_new = sc.fv.cwiseProduct(st.v) + sc.fq.cwiseProduct(st.q) + sc.fa * abar;
  w.q_new = sc.qv.cwiseProduct(st.v) + sc.qq.cwiseProduct(st.q) + sc.qa * abar;
  contacts_of_step(sc, st, w, t);
  return end_of_step(sc, st, w, t, work, history, monitor);
}

}  // namespace

void contacts(const Scheme& sc, State& st, Work& w, Tally& t) { contacts_of_step(sc, st, w, t); }

bool finish_step(const Scheme& sc, State& st, Work& w, Tally& t, std::vector<double>* history) {
  return end_of_step(sc, st, w, t, 0.0, history, nullptr);
}

bool advance(const Scheme& sc, State& st, Work& w, Tally& t, long k_end, std::vector<double>* history,
             StepMonitor* monitor) {
  return drive(sc.load, st.k, k_end,
               [&](double abar, double work) { return step(sc, st, w, t, abar, work, history, monitor); });
}

}  // namespace pb::moreau_jean::dynamic
