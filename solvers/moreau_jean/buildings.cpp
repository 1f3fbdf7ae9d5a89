#include "solvers/moreau_jean/buildings.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "cases/text.hpp"
#include "kit/fixed_step.hpp"
#include "kit/lcp/lemke.hpp"
#include "kit/lcp/small.hpp"
#include "kit/run_limits.hpp"
#include "solvers/moreau_jean/loop_common.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"

namespace pb::moreau_jean {

// A namespace of its own: a unity build puts this file beside moreau_jean.cpp, whose Scheme,
// State, step and kChunk (stepper.hpp, its anonymous namespace) are the single oscillators'.
namespace floors {

namespace {

using buildings::BuildingsResult;
using buildings::FloorPeaks;
using Sparse = Eigen::SparseMatrix<double>;

// LDL^T of W_hat in the floors' own order. W_hat is block diagonal, one block per building,
// each block tridiagonal where the damping is Rayleigh (C = a0 M + a1 K) and full where it is
// modal; without reordering the factor has no fill-in outside the blocks' own profile: banded
// (bidiagonal L) for Rayleigh, dense per building for modal. One code path for both, and
// nothing in a step but sparse products and two triangular solves.
using Factor = Eigen::SimplicialLDLT<Sparse, Eigen::Lower, Eigen::NaturalOrdering<int>>;

// Steps between two looks at the clock: a whole number of the load recurrence's
// resynchronisation periods, so that where a chunk ends never changes a result.
constexpr long kChunk = 64 * kResync;

// What a run never changes (built once, before the loop).
class Scheme {
 public:
  Scheme(const BuildingModel& md, double step, const Settings& set)
      : n(md.n_floors),
        nc(static_cast<int>(md.contacts.size())),
        h(step),
        h_old(step * (1.0 - set.theta)),
        h_new(step * set.theta),
        gamma_h(set.gamma * step),
        eps(md.scene.eps),
        delta(md.scene.delta),
        plastic(kRestitutionFloor * md.speed_scale()),
        bound(1e6 * md.length_scale()),
        contacts(md.contacts),
        load(make_pulse_load(md.scene.pulse, h, set.variant == kEndSamples ? LoadRule::end_samples : LoadRule::step_mean,
                             set.theta)) {
    const double theta = set.theta;
    const Sparse k = md.K.sparseView(), c = md.C.sparseView();
    // The step's smooth impulse: W_hat dv = smooth (v, u) + mass abar, one sparse product.
    Eigen::MatrixXd both(n, 2 * n);
    both << -h * (md.C + (h * theta) * md.K), -h * md.K;
    smooth = both.sparseView();
    mass = -h * md.m;
    Sparse w = (h * theta) * c + (h * h * theta * theta) * k;
    for (int i = 0; i < n; ++i) w.coeffRef(i, i) += md.m(i);
    w_hat.compute(w);
    if (w_hat.info() != Eigen::Success) throw std::runtime_error("W_hat = M + h theta C + h^2 theta^2 K: not factorised");
    contact_rows(md);
  }

  int n, nc;
  double h, h_old, h_new;  // h, h (1 - theta), h theta
  double gamma_h;          // the activation look-ahead gamma h
  double eps, delta;
  double plastic;  // an approach slower than this is no impact: kRestitutionFloor a_p / w_p
  double bound;    // |u| above this is divergence
  // -h [C + h theta K, K], by rows: each entry of the product is one row's sum, written once.
  Eigen::SparseMatrix<double, Eigen::RowMajor> smooth;
  Eigen::VectorXd mass;   // -h M 1
  Factor w_hat;
  Eigen::MatrixXd y;         // W_hat^-1 W: the velocity change per unit impulse of each contact
  Eigen::MatrixXd delassus;  // W^T W_hat^-1 W, the LCP's matrix (symmetric positive definite)
  std::vector<FloorContact> contacts;
  // The rows of column j of y that are not zero: the floors of its two buildings, which are
  // consecutive in the global numbering.
  std::vector<int> rows_from, rows_size;
  PulseLoad load;

 private:
  void contact_rows(const BuildingModel& md) {
    Eigen::MatrixXd w = Eigen::MatrixXd::Zero(n, nc);
    for (int j = 0; j < nc; ++j) {
      const FloorContact& fc = contacts[static_cast<std::size_t>(j)];
      w(fc.i_right, j) = 1.0;
      w(fc.i_left, j) = -1.0;
      rows_from.push_back(md.first[static_cast<std::size_t>(fc.left)]);
      rows_size.push_back(md.scene.buildings[static_cast<std::size_t>(fc.left)].floors() +
                          md.scene.buildings[static_cast<std::size_t>(fc.right)].floors());
    }
    y = w_hat.solve(w);
    const Eigen::MatrixXd a = w.transpose() * y;
    delassus = 0.5 * (a + a.transpose());  // symmetric to the last bit
  }
};

struct State {
  Eigen::VectorXd x;           // (v, u): the floors' velocities, then their displacements
  auto v() { return x.head(x.size() / 2); }
  auto u() { return x.tail(x.size() / 2); }
  Eigen::VectorXd g, rate;     // per contact: gaps and gap rates W^T v
  std::vector<char> active;    // in the index set of the last step
  long k = 0;                  // steps taken: the state is at t_k = k h
};

State rest(const Scheme& sc) {
  State st;
  st.x.setZero(2 * sc.n);
  st.g.setConstant(sc.nc, sc.delta);
  st.rate.setZero(sc.nc);
  st.active.assign(static_cast<std::size_t>(sc.nc), 0);
  return st;
}

// Why a step stopped the run.
enum class Stop { none, lcp, not_finite, diverged };

// The scratch of a step, sized once.
struct Work {
  Eigen::VectorXd r, dv, v_new;   // per floor
  Eigen::VectorXd q, p;           // per contact: the LCP's vector and the impulses
  std::vector<char> now;          // per contact: in this step's index set
  std::vector<int> act;           // the active contacts, first `count` of them
  Eigen::MatrixXd a_lcp;          // three or more active contacts: Lemke's problem, all contacts
  Eigen::VectorXd q_lcp, z_lcp;
  lcp::LemkeWorkspace lemke;
  Stop stop = Stop::none;
  lcp::Status lcp_status = lcp::Status::solved;

  explicit Work(const Scheme& sc) {
    r.setZero(sc.n);
    dv.setZero(sc.n);
    v_new.setZero(sc.n);
    q.setZero(sc.nc);
    p.setZero(sc.nc);
    now.assign(static_cast<std::size_t>(sc.nc), 0);
    act.assign(static_cast<std::size_t>(sc.nc), 0);
    a_lcp.setZero(sc.nc, sc.nc);
    q_lcp.setZero(sc.nc);
    z_lcp.setZero(sc.nc);
    lemke.reserve(sc.nc, 1);
  }
};

// Newton's LCP over three or more active contacts, by Lemke on the problem of every contact
// with the inactive ones decoupled (their row of A its diagonal alone, their q positive:
// their impulse is 0 and never enters the path). One size for every step, so the workspace
// reserved before the loop serves them all; the q given them is the active ones' largest
// |q|, which keeps Lemke's relative tolerances in the problem's own units.
bool solve_many(const Scheme& sc, Work& w, int count) {
  double q_max = 0.0;
  for (int a = 0; a < count; ++a) q_max = std::max(q_max, std::abs(w.q(w.act[static_cast<std::size_t>(a)])));
  w.a_lcp.setZero();
  w.q_lcp.setConstant(q_max);
  for (int j = 0; j < sc.nc; ++j) w.a_lcp(j, j) = sc.delassus(j, j);
  for (int a = 0; a < count; ++a) {
    const int i = w.act[static_cast<std::size_t>(a)];
    w.q_lcp(i) = w.q(i);
    for (int b = 0; b < count; ++b) {
      const int j = w.act[static_cast<std::size_t>(b)];
      w.a_lcp(i, j) = sc.delassus(i, j);
    }
  }
  w.lcp_status = lcp::lemke(w.a_lcp, w.q_lcp, w.z_lcp, w.lemke).status;
  if (w.lcp_status != lcp::Status::solved) return false;
  for (int a = 0; a < count; ++a) {
    const int i = w.act[static_cast<std::size_t>(a)];
    w.p(i) = w.z_lcp(i);
  }
  return true;
}

// The impulses P of the active contacts (w.act[0, count)) on the LCP vector w.q: closed forms
// for one and two (exact, lcp/small.hpp), Lemke beyond. False if Lemke found no solution.
bool impulses(const Scheme& sc, Work& w, int count) {
  bool any_approach = false;
  for (int a = 0; a < count; ++a) {
    const int j = w.act[static_cast<std::size_t>(a)];
    w.p(j) = 0.0;
    any_approach |= w.q(j) < 0.0;
  }
  if (!any_approach) return true;  // P = 0 solves it: every active contact separates freely
  if (count == 1) {
    const int j = w.act[0];
    w.p(j) = lcp::solve1(sc.delassus(j, j), w.q(j));
    return true;
  }
  if (count == 2) {
    const int i = w.act[0], j = w.act[1];
    Eigen::Matrix2d a;
    a << sc.delassus(i, i), sc.delassus(i, j), sc.delassus(j, i), sc.delassus(j, j);
    const Eigen::Vector2d z = lcp::solve2(a, Eigen::Vector2d(w.q(i), w.q(j)));
    w.p(i) = z(0);
    w.p(j) = z(1);
    return true;
  }
  return solve_many(sc, w, count);
}

// The contacts of the step from t_k on the free velocities in w.v_new: the index set, Newton's
// law on it, the impulses applied, the impacts counted. False if the LCP failed.
bool contacts(const Scheme& sc, State& st, Work& w, FloorPeaks& peaks) {
  int count = 0;
  for (int j = 0; j < sc.nc; ++j) {
    const bool in = st.g(j) + sc.gamma_h * st.rate(j) <= 0.0;
    w.now[static_cast<std::size_t>(j)] = in ? 1 : 0;
    if (in) w.act[static_cast<std::size_t>(count++)] = j;
  }
  if (count > 0) {
    for (int a = 0; a < count; ++a) {
      const int j = w.act[static_cast<std::size_t>(a)];
      const FloorContact& fc = sc.contacts[static_cast<std::size_t>(j)];
      w.q(j) = (w.v_new(fc.i_right) - w.v_new(fc.i_left)) + sc.eps * st.rate(j);
    }
    if (!impulses(sc, w, count)) return false;
    const double t = static_cast<double>(st.k + 1) * sc.h;  // seen at the step's end, as the shell's
    for (int a = 0; a < count; ++a) {
      const int j = w.act[static_cast<std::size_t>(a)];
      const auto ju = static_cast<std::size_t>(j);
      if (w.p(j) > 0.0) {
        const int from = sc.rows_from[ju], size = sc.rows_size[ju];
        w.v_new.segment(from, size) += w.p(j) * sc.y.col(j).segment(from, size);
      }
      if (!st.active[ju] && -st.rate(j) > sc.plastic) peaks.impact(ju, t, -st.rate(j));
    }
  }
  st.active.swap(w.now);
  return true;
}

// One step from t_k under the ground load abar; false when the run must stop (w.stop says why).
bool step(const Scheme& sc, State& st, Work& w, FloorPeaks& peaks, double abar) {
  w.r = abar * sc.mass;
  w.r.noalias() += sc.smooth * st.x;
  w.dv = sc.w_hat.solve(w.r);
  w.v_new = st.v() + w.dv;
  if (sc.nc > 0 && !contacts(sc, st, w, peaks)) {
    w.stop = Stop::lcp;
    return false;
  }
  st.u() += sc.h_old * st.v() + sc.h_new * w.v_new;
  st.v() = w.v_new;
  ++st.k;
  for (int j = 0; j < sc.nc; ++j) {
    const FloorContact& fc = sc.contacts[static_cast<std::size_t>(j)];
    st.g(j) = sc.delta + (st.x(sc.n + fc.i_right) - st.x(sc.n + fc.i_left));
    st.rate(j) = st.x(fc.i_right) - st.x(fc.i_left);
  }
  if (!std::isfinite(st.x.sum())) {  // a NaN or inf anywhere makes the sum so
    w.stop = Stop::not_finite;
    return false;
  }
  if (!(st.u().cwiseAbs().maxCoeff() <= sc.bound)) {
    w.stop = Stop::diverged;
    return false;
  }
  peaks.sample(static_cast<double>(st.k) * sc.h, st.u().data());
  return true;
}

// Runs the steps to n in chunks, looking at the deadline between them; the status and
// message of a run that stopped early go into r.
void run(const Scheme& sc, long n, const Settings& set, BuildingsResult& r, FloorPeaks& peaks) {
  State st = rest(sc);
  Work w(sc);
  peaks.sample(0.0, st.u().data());
  Deadline deadline(set);
  while (st.k < n) {
    const long end = std::min(n, st.k + kChunk);
    if (!drive(sc.load, st.k, end, [&](double abar, double) { return step(sc, st, w, peaks, abar); })) break;
    if (st.k < n && deadline.passed(st.k)) {
      r.status = Status::time_limit;
      r.message = deadline.reason() + " at t = " + format_number(static_cast<double>(st.k) * sc.h);
      break;
    }
  }
  r.events = st.k;
  const std::string where = " at step " + std::to_string(st.k) + " (t = " + format_number(static_cast<double>(st.k) * sc.h) + ")";
  if (w.stop == Stop::lcp) {
    r.status = Status::failed;
    r.message = "the impact LCP (Lemke) ended " + std::string(lcp::name(w.lcp_status)) + where;
  } else if (w.stop == Stop::not_finite) {
    r.status = Status::nan;
    r.message = "non-finite state" + where;
  } else if (w.stop == Stop::diverged) {
    r.status = Status::diverged;
    r.message = "|u| above 1e6 a_p/w_p^2" + where;
  }
}

}  // namespace

}  // namespace floors

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings) {
  if (std::string why = validate(model.scene); !why.empty()) return buildings::failed(why);
  if (std::string why = check(settings); !why.empty()) return buildings::failed(why);
  buildings::BuildingsResult r;
  long n = 0;
  if (!buildings::plan_steps(model, settings, kDefaultSteps, r, n)) return r;
  buildings::FloorPeaks peaks(model);
  try {
    const floors::Scheme scheme(model, r.step, settings);
    floors::run(scheme, n, settings, r, peaks);
  } catch (const std::exception& e) {
    r.status = Status::failed;
    r.message = e.what();
  }
  peaks.into(r);
  return r;
}

}  // namespace pb::moreau_jean
