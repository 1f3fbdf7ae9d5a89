#include "solvers/buildings_reference/reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>
#include <utility>

#include "solvers/buildings_reference/motion.hpp"
#include "solvers/buildings_reference/search.hpp"
#include "solvers/buildings_reference/stuck.hpp"
#include "kit/lcp/small.hpp"
#include "kit/run_limits.hpp"
#include "kit/lex_sign.hpp"

namespace pb::buildings {

namespace {

// Every tolerance is relative to the pulse's scales (L = a_p / w_p^2, V = a_p / w_p, the
// shortest period), as the single oscillators' reference's are: a scene scaled in its masses,
// stiffnesses and load is solved identically up to round-off.
struct Tolerances {
  double gap;     // a gap below this is closed
  double speed;   // an approach slower than this is plastic (it ends an accumulation)
  double lex;     // relative size below which a Taylor coefficient counts as zero
  double floor;   // the shortest window a search resolves (s)
  double settle;  // how long a just-opened contact may take to show a positive gap (s)
};

// Gauss-Legendre nodes and weights on [-1, 1] for n = 4, 8, 16, by Newton on P_n from
// Tricomi's guesses (to the last bit: the iteration stops where it no longer moves).
struct GaussRule {
  int n = 0;
  std::array<double, 16> x{}, w{};
  explicit GaussRule(int points) : n(points) {
    for (int i = 0; i < n; ++i) {
      double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1.0);
        const double step = p1 / dp;
        z -= step;
        if (std::abs(step) < 1e-17) break;
      }
      x[static_cast<std::size_t>(i)] = z;
      w[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
  }
};

// The rule for a panel of length h of integrands of rates up to r: its error, about
// c_n (r h)^(2n) of the panel's scale (c_4 = 5.6e-10, c_8 = 1.7e-23, c_16 = 3.2e-55), below
// 1e-16 for r h <= 0.14 with 4 points and <= 2.6 with 8; longer panels are cut to r h <= 16
// (1e-14) for 16.
const GaussRule& gauss_rule(double rh) {
  static const GaussRule g4(4), g8(8), g16(16);
  return rh <= 0.14 ? g4 : rh <= 2.6 ? g8 : g16;
}

// One way of deciding the contact LCP: Taylor coefficients within tol (relative) of zero
// defer to the next one, down to `depth` derivatives of a force.
struct Pass {
  double tol;
  int depth;
};

// What is known of one set of stuck contacts: its reduced system, and its modes once a
// segment needs them (the LCP's candidates need only the former).
struct Entry {
  Reduced reduced;
  std::unique_ptr<Modal> modal;
};

class Solver {
 public:
  // free: the model's contacts are not contacts but floor pairs watched (free_motion): no
  // closure is an event, and each pair's relative displacement is searched both ways.
  Solver(const BuildingModel& md, const Settings& settings, bool free = false)
      : md_(md),
        free_(free),
        nf_(md.n_floors),
        nc_(static_cast<int>(md.contacts.size())),
        deadline_(settings),
        cap_(settings.step_cap > 0 ? settings.step_cap : 1000000),
        tol_scale_(settings.tol_scale > 0.0 ? settings.tol_scale : 1.0) {
    const double eps = std::numeric_limits<double>::epsilon();
    tol_.gap = 1e-10 * tol_scale_ * md.length_scale();
    tol_.speed = 1e-7 * tol_scale_ * md.speed_scale();
    tol_.lex = 1e-9 * tol_scale_;
    tol_.floor = std::max(1e-13 * md.t_min, 8.0 * eps * md.t_end);
    tol_.settle = 1e-4 * md.t_min;
    const auto n = static_cast<std::size_t>(nf_), c = static_cast<std::size_t>(nc_);
    u_.assign(n, 0.0);
    v_.assign(n, 0.0);
    g_.assign(c, md.scene.delta);
    stuck_.assign(c, 0);
    before_.assign(c, 0);
    trial_.assign(c, 0);
    impacted_.assign(c, 0);
    misfit_.assign(c, 0);
    force_scale_.resize(c);
    for (std::size_t j = 0; j < c; ++j) {
      const FloorContact& fc = md.contacts[j];
      force_scale_[j] = md.a_p / (1.0 / md.m(fc.i_left) + 1.0 / md.m(fc.i_right));
    }
    rate_ = md.w_p;
    int tallest = 1;
    for (const BuildingModes& m : md.modes) {
      rate_ = std::max(rate_, m.w(m.w.size() - 1));
      tallest = std::max(tallest, static_cast<int>(m.w.size()));
    }
    // The relative motion of floor j starts some 2 j derivatives after the load's (a storey's
    // deformation reaches one floor further up every second derivative).
    depth_ = std::min(4 + 2 * tallest, 24);
    taylor_.assign(static_cast<std::size_t>(depth_ + 3) * n, 0.0);
    coef_.assign(static_cast<std::size_t>(depth_ + 3), 0.0);
    q_.assign(n, 0.0);
    qd_.assign(n, 0.0);
    vel_.assign(n, 0.0);
    cv_.assign(n, 0.0);
    const std::size_t stride = 2 * n + kMaxSinusoids;  // modes and sinusoids
    node_.assign(16 * stride, 0.0);
    step_.assign(stride, 0.0);
    panel_.assign(stride, 0.0);
    at_.assign(stride, 0.0);
    candidates_.reserve(c);
    count_.reserve(n);
    order_.reserve(c);
    reach_.assign(c, 0.0);
    motion_.reserve(nf_, nc_);
    peaks_.assign(2 * n, Peak{});
    quantity_.resize(2 * n);
    for (int i = 0; i < nf_; ++i) {
      quantity_[static_cast<std::size_t>(i)] = motion_.floor(i);
      quantity_[static_cast<std::size_t>(nf_ + i)] = motion_.drift(i);
    }
    peak_search_.reserve(2 * nf_);
    closing_.assign(c, Peak{});
    opening_.assign(c, Peak{});
    res_.contacts.resize(c);
    for (std::size_t j = 0; j < c; ++j) {
      res_.contacts[j].left = md.contacts[j].left;
      res_.contacts[j].right = md.contacts[j].right;
      res_.contacts[j].floor = md.contacts[j].floor;
    }
    res_.t_end = md.t_end;
  }

  BuildingsResult run() {
    try {
      events();
    } catch (const OutOfTime&) {
      res_.status = Status::time_limit;
      std::ostringstream msg;
      msg << deadline_.reason() << " (t = " << t_ << " of " << md_.t_end << ")";
      res_.message = msg.str();
    } catch (const NonFinite&) {
      fail(Status::nan, "the closed-form motion is not finite");
    }
    return finish();
  }

 private:
  void events() {
    if (!free_ && !start()) return;
    const Pulse& pulse = md_.scene.pulse;
    while (t_ < md_.t_end) {
      const LoadPiece piece = pulse.piece(t_);
      const double seg_end = std::min(piece.end, md_.t_end);
      Entry& e = entry(stuck_);
      const Modal& mo = modal(e);
      if (!mo.ok) {
        fail(Status::failed, mo.why);
        return;
      }
      motion_.build(md_, e.reduced, mo, u_.data(), v_.data(), g_.data(), piece, t_, seg_end);
      double b = seg_end;
      int which = -1;
      // The contacts in the order of the earliest time their quadratic lower bound lets them
      // reach zero: the earliest event is then usually found first, and the others' searches
      // stop at it. (Ties keep the contacts' order: the event is the lowest-numbered one's.)
      if (!free_) {
        order_contacts(b);
        for (int j : order_) {
          const double r = root(j, b);
          if (!std::isnan(r) && (r < b || (r == b && (which < 0 || j < which)))) {
            b = r;
            which = j;
          }
        }
      }
      peaks(b);
      if (free_) watch(b);
      integrate(piece, b);
      advance(b);
      if (++res_.events > cap_) {
        fail(Status::step_cap, "more than " + std::to_string(cap_) + " events");
        return;
      }
      if (deadline_.tick()) throw OutOfTime{};
      if (which < 0 && t_ >= md_.t_end) break;
      const double e_before = md_.energy(u_.data(), v_.data());
      bool ok;
      if (which >= 0 && !stuck_[static_cast<std::size_t>(which)]) {
        g_[static_cast<std::size_t>(which)] = 0.0;
        ok = impact(which);
      } else {
        // A force reached zero, or the load reached a breakpoint (it may jump): the stuck
        // contacts anew.
        candidates_.clear();
        for (int j = 0; j < nc_; ++j)
          if (stuck_[static_cast<std::size_t>(j)]) candidates_.push_back(j);
        ok = resolve();
      }
      if (!ok) return;
      account(e_before);
    }
  }

  // t = 0: contacts closed at rest (a gap of 0) are decided by the contact LCP.
  bool start() {
    candidates_.clear();
    for (int j = 0; j < nc_; ++j)
      if (g_[static_cast<std::size_t>(j)] <= tol_.gap) candidates_.push_back(j);
    if (candidates_.empty()) return true;
    const double e_before = md_.energy(u_.data(), v_.data());
    if (!resolve()) return false;
    account(e_before);
    return true;
  }

  Entry& entry(const std::vector<char>& stuck) {
    auto it = cache_.find(stuck);
    if (it == cache_.end()) it = cache_.emplace(stuck, Entry{make_reduced(md_, stuck), nullptr}).first;
    return it->second;
  }

  const Modal& modal(Entry& e) {
    if (!e.modal) e.modal = std::make_unique<Modal>(make_modal(md_, e.reduced));
    return *e.modal;
  }

  // order_: the contacts by the time f + f' s - max|f''| s^2 / 2 (a gap, or a stuck contact's
  // force) first reaches zero, the earliest first.
  void order_contacts(double b) {
    order_.clear();
    for (int j = 0; j < nc_; ++j) {
      double out[2], bd[kMaxOrder + 1];
      motion_.eval(motion_.contact(j), t_, out, 2);
      motion_.bounds(motion_.contact(j), t_, bd);
      double reach = 0.0;
      if (out[0] >= 0.0) {
        const double disc = std::sqrt(out[1] * out[1] + 2.0 * bd[2] * out[0]);
        reach = bd[2] > 0.0 ? (out[1] >= 0.0 ? (out[1] + disc) / bd[2] : 2.0 * out[0] / (disc - out[1]))
                            : (out[1] >= 0.0 ? b - t_ : -out[0] / out[1]);
      }
      reach_[static_cast<std::size_t>(j)] = std::isfinite(reach) ? reach : b - t_;
      order_.push_back(j);
    }
    std::stable_sort(order_.begin(), order_.end(),
                     [&](int x, int y) { return reach_[static_cast<std::size_t>(x)] < reach_[static_cast<std::size_t>(y)]; });
  }

  // The first event of contact j before b: an open one's closure, a stuck one's force
  // falling to zero (one that stays within its noise of zero has none: floors moving alike).
  double root(int j, double b) {
    const auto k = static_cast<std::size_t>(j);
    const Track f{&motion_, motion_.contact(j), 0.0};
    if (stuck_[k]) {
      const double noise = tol_.lex * force_scale_[k];
      double bd[kMaxOrder + 1];
      f.bounds(t_, bd);
      if (std::abs(f.mean()) + bd[0] < noise) return std::numeric_limits<double>::quiet_NaN();
      return first_root(f, t_, b, tol_.floor, tol_.settle, noise, deadline_);
    }
    return first_root(f, t_, b, tol_.floor, tol_.settle, tol_.gap, deadline_);
  }

  // Every floor's and storey's largest |value| on [t_, b]: quantities 0 .. 2 nf - 1 of the
  // Motion, floors then drifts, as peaks_ holds them.
  void peaks(double b) { peak_search_.run(motion_, quantity_.data(), peaks_.data(), 2 * nf_, t_, b, tol_.floor, deadline_); }

  // The free watch on [t_, b]: each pair's gap quantity (delta 0: u_right - u_left) both ways.
  void watch(double b) {
    for (int j = 0; j < nc_; ++j) {
      const auto k = static_cast<std::size_t>(j);
      max_both(Track{&motion_, motion_.contact(j), 0.0}, t_, b, tol_.floor, opening_[k], closing_[k], deadline_);
    }
  }

  // The ground's work and the dampers' on [t_, b], by Gauss-Legendre on panels short enough
  // for its error to be below 1e-14 of a panel's scale (gauss_rule): the integrands are
  // products of the motion's terms, of rates up to twice the fastest. The nodes' exponentials are the panel's times the node's offset, the panel's stepped by
  // products: a few ulps of drift over a segment, far below the check's 1e-9.
  void integrate(const LoadPiece& piece, double b) {
    if (!(b > t_)) return;
    const double span = b - t_;
    const double rate = std::max(2.0 * motion_.fastest(), 1e-300);
    const long panels = std::max(1L, static_cast<long>(std::ceil(span * rate / 16.0)));
    const double h = span / static_cast<double>(panels);
    const GaussRule& gl = gauss_rule(rate * h);
    const auto nodes = static_cast<std::size_t>(gl.n);
    const auto nk = static_cast<std::size_t>(motion_.modes()), nj = static_cast<std::size_t>(motion_.sines());
    const std::size_t stride = nk + nj;
    for (std::size_t k = 0; k < nodes; ++k)
      motion_.exp_factors(0.5 * h * (1.0 + gl.x[k]), &node_[k * stride], &node_[k * stride + nk]);
    motion_.exp_factors(h, step_.data(), step_.data() + nk);
    std::fill(panel_.begin(), panel_.begin() + static_cast<std::ptrdiff_t>(stride), cplx(1.0));
    double input = 0.0, damped = 0.0;
    for (long p = 0; p < panels; ++p) {
      const double start = t_ + static_cast<double>(p) * h;
      for (std::size_t k = 0; k < nodes; ++k) {
        const double t = start + 0.5 * h * (1.0 + gl.x[k]);
        for (std::size_t m = 0; m < stride; ++m) at_[m] = panel_[m] * node_[k * stride + m];
        motion_.floor_velocities(t, at_.data(), at_.data() + nk, vel_.data());
        double momentum = 0.0;
        for (int i = 0; i < nf_; ++i) momentum += md_.m(i) * vel_[static_cast<std::size_t>(i)];
        const Eigen::Map<const Eigen::VectorXd> vv(vel_.data(), nf_);
        Eigen::Map<Eigen::VectorXd> cv(cv_.data(), nf_);
        cv.noalias() = md_.C * vv;
        input += gl.w[k] * (-piece.accel(t) * momentum);
        damped += gl.w[k] * vv.dot(cv);
      }
      for (std::size_t m = 0; m < stride; ++m) panel_[m] *= step_[m];
    }
    input_ += 0.5 * h * input;
    damped_ += 0.5 * h * damped;
  }

  void advance(double b) {
    double out[2];
    for (int i = 0; i < nf_; ++i) {
      motion_.eval(motion_.floor(i), b, out, 2);
      u_[static_cast<std::size_t>(i)] = out[0];
      v_[static_cast<std::size_t>(i)] = out[1];
    }
    for (int j = 0; j < nc_; ++j) {
      const auto k = static_cast<std::size_t>(j);
      if (stuck_[k]) {
        g_[k] = 0.0;
        continue;
      }
      motion_.eval(motion_.contact(j), b, out, 1);
      g_[k] = out[0];
      if (out[0] < 0.0 && !free_) res_.min_gap = std::min(res_.min_gap, out[0]);
    }
    t_ = b;
  }

  double rate(int j) const {
    const FloorContact& fc = md_.contacts[static_cast<std::size_t>(j)];
    return v_[static_cast<std::size_t>(fc.i_right)] - v_[static_cast<std::size_t>(fc.i_left)];
  }

  // Newton's law over the set S of the closing contact, the stuck ones and every other contact
  // closed within tol_gap and approaching, level by level: contacts at different floors share
  // no floor, so G = W^T M^-1 W is block diagonal with a block per floor level of one contact
  // (two buildings) or two (three, sharing the middle one's floor). A separating contact is
  // left out: Newton's law over it would let it leave approaching (z = g'+ + eps g'- >= 0 holds
  // with g'+ < 0 where g'- > 0). Then the contact LCP on those left at rest relative to each other.
  bool impact(int which) {
    closed_.clear();
    for (int j = 0; j < nc_; ++j) {
      const auto k = static_cast<std::size_t>(j);
      if (j == which || stuck_[k] || (g_[k] <= tol_.gap && rate(j) < 0.0)) closed_.push_back(j);
    }
    for (int j : closed_) {
      const double r = rate(j);
      if (r < -tol_.speed) {
        ContactResult& c = res_.contacts[static_cast<std::size_t>(j)];
        ++c.impacts;
        if (!(c.first_impact <= t_)) c.first_impact = t_;
        if (!(c.impact_velocity_max >= -r)) c.impact_velocity_max = -r;
      }
    }
    // closed_ is ascending, and contacts are numbered pair by pair (buildings 0-1 first): a
    // level's second contact, if any, comes later and is the right-hand pair's.
    for (std::size_t a = 0; a < closed_.size(); ++a) {
      const int j1 = closed_[a];
      if (impacted_[static_cast<std::size_t>(j1)]) continue;
      int j2 = -1;
      for (std::size_t b = a + 1; b < closed_.size(); ++b)
        if (md_.contacts[static_cast<std::size_t>(closed_[b])].i_left == md_.contacts[static_cast<std::size_t>(j1)].i_right)
          j2 = closed_[b];
      impact_level(j1, j2);
    }
    for (int j : closed_) impacted_[static_cast<std::size_t>(j)] = 0;
    candidates_.clear();
    for (int j : closed_) {
      if (rate(j) <= tol_.speed) {
        candidates_.push_back(j);
      } else {
        stuck_[static_cast<std::size_t>(j)] = 0;
      }
    }
    return resolve();
  }

  // Newton's impact on one level's closed contacts j1 (and j2, or -1): find Lambda >= 0 with
  // (1 + eps) g'- + G Lambda >= 0, complementary; plastic (eps = 0) when the fastest approach
  // is below tol_speed, which ends an accumulation of impacts.
  void impact_level(int j1, int j2) {
    impacted_[static_cast<std::size_t>(j1)] = 1;
    if (j2 >= 0) impacted_[static_cast<std::size_t>(j2)] = 1;
    const double r1 = rate(j1), r2 = j2 >= 0 ? rate(j2) : 0.0;
    const double approach = std::min(r1, r2);
    if (!(approach < 0.0)) return;
    const double eps = -approach > tol_.speed ? md_.scene.eps : 0.0;
    const FloorContact& c1 = md_.contacts[static_cast<std::size_t>(j1)];
    const double inv_l1 = 1.0 / md_.m(c1.i_left), inv_r1 = 1.0 / md_.m(c1.i_right);
    if (j2 < 0) {
      const double lambda = lcp::solve1(inv_l1 + inv_r1, (1.0 + eps) * r1);
      apply(c1, lambda);
      return;
    }
    const FloorContact& c2 = md_.contacts[static_cast<std::size_t>(j2)];
    const double inv_r2 = 1.0 / md_.m(c2.i_right);
    Eigen::Matrix2d gm;
    gm << inv_l1 + inv_r1, -inv_r1, -inv_r1, inv_r1 + inv_r2;  // c1's right floor is c2's left
    const Eigen::Vector2d lambda = lcp::solve2(gm, Eigen::Vector2d((1.0 + eps) * r1, (1.0 + eps) * r2));
    apply(c1, lambda(0));
    apply(c2, lambda(1));
  }

  void apply(const FloorContact& c, double lambda) {
    if (!(lambda > 0.0)) return;
    v_[static_cast<std::size_t>(c.i_left)] -= lambda / md_.m(c.i_left);
    v_[static_cast<std::size_t>(c.i_right)] += lambda / md_.m(c.i_right);
  }

  // The acceleration LCP (DERIVATION.md §5) on candidates_ (closed, at rest relative to each
  // other): which of them stick. Their gaps are closed exactly first (floors moved within
  // tol_gap, each cluster about its centre of mass); the floors that stick then share their
  // cluster's velocity (its momentum kept: this only loses energy).
  bool resolve() {
    before_ = stuck_;
    std::fill(stuck_.begin(), stuck_.end(), 0);
    if (candidates_.empty()) return true;
    std::fill(trial_.begin(), trial_.end(), 0);
    for (int j : candidates_) {
      trial_[static_cast<std::size_t>(j)] = 1;
      g_[static_cast<std::size_t>(j)] = 0.0;
    }
    place(entry(trial_).reduced, false);
    if (!decide()) return false;
    place(entry(stuck_).reduced, true);
    for (std::size_t j = 0; j < stuck_.size(); ++j)
      if (stuck_[j] && !before_[j]) ++res_.contacts[j].contact_phases;
    return true;
  }

  // Puts the floors of every multi-floor cluster of r at the cluster's position plus their
  // offsets (and at its velocity, when `velocities`).
  void place(const Reduced& r, bool velocities) {
    r.reduce(u_.data(), v_.data(), q_.data(), qd_.data());
    count_.assign(static_cast<std::size_t>(r.n), 0);
    for (int c : r.cluster) ++count_[static_cast<std::size_t>(c)];
    for (int i = 0; i < nf_; ++i) {
      const auto c = static_cast<std::size_t>(r.cluster[static_cast<std::size_t>(i)]);
      if (count_[c] < 2) continue;
      u_[static_cast<std::size_t>(i)] = q_[c] + r.offset(i);
      if (velocities) v_[static_cast<std::size_t>(i)] = qd_[c];
    }
  }

  // Which candidates stick: every force of the stuck ones and every gap of the others
  // lexicographically non-negative in its Taylor coefficients at t (DERIVATION.md §5), which
  // decides degenerate starts (zero force and zero relative acceleration: a gap of 0 at rest)
  // by the first derivative that does not vanish. Up to 8 candidates every set is tried, all
  // stuck first; more, a set is grown from all stuck by flipping the contacts that do not fit.
  bool decide() {
    const int n = static_cast<int>(candidates_.size());
    const LoadPiece piece = md_.scene.pulse.piece(t_);
    for (const Pass pass : {Pass{tol_.lex, depth_}, Pass{0.0, depth_}, Pass{tol_.lex, 1}}) {
      if (n <= 8) {
        for (int mask = (1 << n) - 1; mask >= 0; --mask) {
          for (int a = 0; a < n; ++a) trial_[static_cast<std::size_t>(candidates_[static_cast<std::size_t>(a)])] = (mask >> a) & 1;
          if (fits(piece, pass, false)) {
            stuck_ = trial_;
            return true;
          }
        }
      } else {
        for (int j : candidates_) trial_[static_cast<std::size_t>(j)] = 1;
        for (int step = 0; step < 2 * n + 2; ++step) {
          if (fits(piece, pass, true)) {
            stuck_ = trial_;
            return true;
          }
          for (int j : candidates_)
            if (misfit_[static_cast<std::size_t>(j)]) trial_[static_cast<std::size_t>(j)] ^= 1;
        }
      }
    }
    std::ostringstream msg;
    msg << "no set of stuck floors fits the acceleration LCP at t = " << t_ << " (" << n << " closed contacts)";
    return fail(Status::failed, msg.str());
  }

  // Whether trial_ fits; with `all_of_them`, every candidate is judged (misfit_ marks those
  // that do not fit), else the first that does not ends the test.
  bool fits(const LoadPiece& piece, const Pass& pass, bool all_of_them) {
    const Reduced& r = entry(trial_).reduced;
    taylor(r, piece, pass.depth + 2);
    const auto n = static_cast<std::size_t>(r.n);
    bool all = true;
    for (int j : candidates_) {
      const auto k = static_cast<std::size_t>(j);
      bool ok;
      if (trial_[k]) {
        for (int d = 0; d < pass.depth; ++d) {
          const double* q = &taylor_[static_cast<std::size_t>(d) * n];
          const double* qd = &taylor_[static_cast<std::size_t>(d + 1) * n];
          double x = d == 0 ? r.L0(j) : 0.0;
          for (std::size_t c = 0; c < n; ++c)
            x += r.Lq(j, static_cast<Eigen::Index>(c)) * q[c] + r.Lv(j, static_cast<Eigen::Index>(c)) * qd[c];
          coef_[static_cast<std::size_t>(d)] = x;
        }
        ok = lex_nonnegative(coef_.data(), pass.depth, force_scale_[k], rate_, pass.tol);


      } else {
        const FloorContact& fc = md_.contacts[k];
        const auto cl = static_cast<std::size_t>(r.cluster[static_cast<std::size_t>(fc.i_left)]);
        const auto cr = static_cast<std::size_t>(r.cluster[static_cast<std::size_t>(fc.i_right)]);
        for (int d = 1; d <= pass.depth + 1; ++d) {
          const double* q = &taylor_[static_cast<std::size_t>(d) * n];
          coef_[static_cast<std::size_t>(d - 1)] = q[cr] - q[cl];
        }
        ok = lex_nonnegative(coef_.data(), pass.depth + 1, md_.a_p / rate_, rate_, pass.tol);


      }
      misfit_[k] = !ok;
      if (!ok) {
        all = false;
        if (!all_of_them) return false;
      }
    }
    return all;
  }

  // Taylor coefficients at t_ (from the right) of the reduced motion of r: q^(d) for
  // d = 0 .. orders - 1, from M_r q'' = f_c - m_r a_g - C_r q' - K_r q.
  void taylor(const Reduced& r, const LoadPiece& piece, int orders) {
    const auto n = static_cast<std::size_t>(r.n);
    double* q = taylor_.data();
    r.reduce(u_.data(), v_.data(), q, q + n);
    // a_g and its derivatives at t_: the polynomial's, then the sinusoids' (s, c) -> (-w c, w s).
    std::array<double, kMaxSinusoids> s{}, c{};
    for (int j = 0; j < piece.n_waves; ++j) {
      s[static_cast<std::size_t>(j)] = piece.waves[static_cast<std::size_t>(j)].s;
      c[static_cast<std::size_t>(j)] = piece.waves[static_cast<std::size_t>(j)].c;
    }
    for (int d = 0; d + 2 < orders; ++d) {
      double ag = d == 0 ? piece.value + piece.slope * (t_ - piece.start) : d == 1 ? piece.slope : 0.0;
      if (d == 0 && piece.slope == 0.0) ag = piece.value;
      for (int j = 0; j < piece.n_waves; ++j) {
        const auto jj = static_cast<std::size_t>(j);
        const double w = piece.waves[jj].w;
        ag += s[jj] * std::sin(w * t_) + c[jj] * std::cos(w * t_);
        const double s_next = -w * c[jj], c_next = w * s[jj];
        s[jj] = s_next;
        c[jj] = c_next;
      }
      const double* qa = q + static_cast<std::size_t>(d) * n;
      const double* qb = q + static_cast<std::size_t>(d + 1) * n;
      double* out = q + static_cast<std::size_t>(d + 2) * n;
      for (std::size_t a = 0; a < n; ++a) {
        double x = (d == 0 ? r.f(static_cast<Eigen::Index>(a)) : 0.0) - r.mass(static_cast<Eigen::Index>(a)) * ag;
        for (std::size_t b = 0; b < n; ++b)
          x -= r.C(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) * qb[b] +
               r.K(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) * qa[b];
        out[a] = x / r.mass(static_cast<Eigen::Index>(a));
      }
    }
  }

  // The event's change of the floors' energy (impacts, merged floors) is taken by the impacts'
  // term; the balance input = kinetic + elastic + damped + impacts is checked here.
  void account(double e_before) {
    const double e = md_.energy(u_.data(), v_.data());
    losses_ += e_before - e;
    made_ = std::max(made_, e - e_before);
    const double scale = std::max(md_.energy_scale(), std::abs(input_));
    error_ = std::max(error_, std::max(std::abs(input_ - (e + damped_ + losses_)), made_) / scale);
  }

  bool fail(Status status, std::string why) {
    res_.status = status;
    std::ostringstream msg;
    msg << why << " (t = " << t_ << ")";
    res_.message = msg.str();
    return false;
  }

  BuildingsResult finish() {
    // The balance at t_end (the state advanced there).
    account(md_.energy(u_.data(), v_.data()));
    res_.energy_error = error_;
    const double e = md_.energy(u_.data(), v_.data());
    double kinetic = 0.0;
    for (int i = 0; i < nf_; ++i) kinetic += 0.5 * md_.m(i) * v_[static_cast<std::size_t>(i)] * v_[static_cast<std::size_t>(i)];
    res_.energies = {input_, kinetic, e - kinetic, damped_, losses_};
    if (free_ && res_.status == Status::ok)
      for (std::size_t j = 0; j < res_.contacts.size(); ++j) {
        res_.contacts[j].closing = closing_[j].value;
        res_.contacts[j].opening = opening_[j].value;
      }
    const std::size_t nb = md_.scene.buildings.size();
    res_.floor_peak.resize(nb);
    res_.floor_peak_time.resize(nb);
    res_.drift_peak.resize(nb);
    res_.drift_peak_time.resize(nb);
    for (std::size_t b = 0; b < nb; ++b) {
      const int n = md_.scene.buildings[b].floors();
      for (int f = 1; f <= n; ++f) {
        const auto i = static_cast<std::size_t>(md_.global(static_cast<int>(b), f));
        const std::size_t d = i + static_cast<std::size_t>(nf_);
        res_.floor_peak[b].push_back(peaks_[i].value);
        res_.floor_peak_time[b].push_back(peaks_[i].t);
        res_.drift_peak[b].push_back(peaks_[d].value);
        res_.drift_peak_time[b].push_back(peaks_[d].t);
      }
    }
    if (res_.status == Status::ok) {
      const double limit = kEnergyCheck * std::max(1.0, tol_scale_);
      std::ostringstream msg;
      if (res_.min_gap < -10.0 * tol_.gap) {
        res_.status = Status::penetration;
        msg << "a gap reached " << res_.min_gap << " m, beyond ten closure tolerances (" << tol_.gap << " m)";
        res_.message = msg.str();
      } else if (!(res_.energy_error <= limit)) {
        res_.status = Status::energy;
        msg << "the energy balance is off by " << res_.energy_error << " of its scale, beyond " << limit;
        res_.message = msg.str();
      }
    }
    return std::move(res_);
  }

  const BuildingModel& md_;
  bool free_;
  int nf_, nc_;
  Deadline deadline_;
  long cap_;
  double tol_scale_;
  Tolerances tol_{};
  double rate_ = 1.0;
  int depth_ = 4;
  double t_ = 0.0;
  std::vector<double> u_, v_, g_;
  std::vector<char> stuck_, before_, trial_, impacted_, misfit_;
  std::vector<double> force_scale_;
  std::vector<int> closed_, candidates_, count_, order_;
  std::vector<double> reach_;
  std::vector<double> taylor_, coef_, q_, qd_, vel_, cv_;
  std::vector<cplx> node_, step_, panel_, at_;  // integrate()'s exponentials
  std::map<std::vector<char>, Entry> cache_;
  Motion motion_;
  std::vector<Peak> peaks_;  // floors, then drifts
  std::vector<int> quantity_;
  PeakSearch peak_search_;
  std::vector<Peak> closing_, opening_;  // the free watch, per contact
  double input_ = 0.0, damped_ = 0.0, losses_ = 0.0, made_ = 0.0, error_ = 0.0;
  BuildingsResult res_;
};

}  // namespace

BuildingsResult solve(const BuildingModel& model, const Settings& settings) {
  return Solver(model, settings).run();
}

BuildingsResult solve(const BuildingScene& scene, const Settings& settings) {
  if (std::string why = validate(scene); !why.empty()) {
    BuildingsResult r;
    r.status = Status::failed;
    r.message = why;
    return r;
  }
  return solve(assemble(scene), settings);
}

BuildingsResult free_motion(const BuildingScene& scene, const Settings& settings) {
  if (std::string why = validate(scene); !why.empty()) {
    BuildingsResult r;
    r.status = Status::failed;
    r.message = why;
    return r;
  }
  // The contacts' floor pairs, at gap 0: each pair's tracked gap is u_right - u_left itself.
  BuildingScene watched = scene;
  watched.no_contact = false;
  watched.delta = 0.0;
  return Solver(assemble(watched), settings, true).run();
}

}  // namespace pb::buildings
