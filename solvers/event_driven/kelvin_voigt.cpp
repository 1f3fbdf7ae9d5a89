#include "solvers/event_driven/kelvin_voigt.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include "kit/contact_elements/contact_law.hpp"
#include "kit/contact_elements/elements.hpp"
#include "kit/run_limits.hpp"

namespace pb::event_driven {

namespace {

using Eigen::MatrixXcd;
using Eigen::MatrixXd;
using Eigen::VectorXcd;
using Eigen::VectorXd;

// Stretches per period of a mode's fastest motion at the start of a mode; then each stretch
// proven with room to spare doubles the next, and each one halved halves it. Measured on the
// work-precision set at K = 1e2 and 1e6: 8, 16 and 32 cost the same CPU to within 4% (32
// takes 6% fewer stretches than 16, each dearer where a mode is new).
constexpr int kStretchesPerPeriod = 16;
// Stretch lengths are the mode's base length times 2^-level, level in [kMinLevel, kMaxLevel];
// the floor (1e-13 T_min) stops the halving first.
constexpr int kMinLevel = -30;
constexpr int kMaxLevel = 70;
// Settings::step_cap counts stretches; without one, 1e8 (about a minute; the runs of the
// shipped sets take 1e3 to 2e4).
constexpr long kDefaultStretchCap = 100'000'000;
// A level's matrix is computed once it has been used this often; before, and only for a
// stretch with |D a D^-1| h <= kTaylorNorm, its increment is summed on the vector (at most
// kMaxTaylorTerms terms: 0.5^18 / 18! is below an ulp).
constexpr int kCacheAfter = 4;
constexpr double kTaylorNorm = 0.5;
constexpr int kMaxTaylorTerms = 24;
// The modal bound rests on the computed eigenvectors: beyond this condition number their
// round-off could eat its margin (kBoundMargin), and the plain bound is used instead.
constexpr double kMaxModalCondition = 1e6;
// Every fourth-derivative bound is doubled: the modal one is computed in floating point.
constexpr double kBoundMargin = 2.0;
// Above this K a pressed contact's gap, about -F / K (1e-15 a_p/w_p^2 at K = 1e14), nears the
// round-off that each stretch's increment leaves in the state (about 1e-16 of it): measured on
// a pair (sine, Pi2 0.5, Pi3 1e-3, eps 0.5), K = 1e12 has the rigid reference's 24 impacts,
// K = 1e13 24 898 at --tol-scale 1 and 68 965 at 0.01, and K = 1e14 a Pi1 2e-3 off the trend.
// The run says so in its message and is unresolved (Result::doubt).
constexpr double kMostVouchedStiffness = 1e12;
// Bodies whose displacements and speeds are all below this, over a_p / w_p^2 and a_p / w_p,
// after the load's end, are at rest (at_rest()).
constexpr double kAtRest = 1e-200;
// The round-off of a tracked function's value, in ulps of the sum of its terms' sizes.
constexpr double kNoise = 64 * std::numeric_limits<double>::epsilon();
// A stretch proven with this factor of room in every check (as its Hermite bound would be at
// twice the length, 2^4; the amplitude bound is evaluated there) lets the next one double.
constexpr double kEasyRoom = 16.0;

// The least and largest value on [0, h] of the cubic Hermite interpolant through (f0, d0)
// at 0 and (f1, d1) at h, plus bend s^2 (0: the interpolant itself), and where they are.
struct Range {
  double lo, hi;
  double t_lo, t_hi;
};

Range hermite_range(double f0, double d0, double f1, double d1, double h, double bend = 0.0) {
  // In tau = s / h: f0 + b tau + c tau^2 + d tau^3, whose rate is b + 2 c tau + 3 d tau^2.
  const double b = h * d0, c = 3.0 * (f1 - f0) - h * (2.0 * d0 + d1) + bend * h * h, d = 2.0 * (f0 - f1) + h * (d0 + d1);
  const double end = f1 + bend * h * h;
  Range r{std::min(f0, end), std::max(f0, end), f0 <= end ? 0.0 : h, f0 >= end ? 0.0 : h};
  const auto visit = [&](double tau) {
    if (!(tau > 0.0 && tau < 1.0)) return;
    const double v = f0 + tau * (b + tau * (c + tau * d));
    if (v < r.lo) r.lo = v, r.t_lo = tau * h;
    if (v > r.hi) r.hi = v, r.t_hi = tau * h;
  };
  const double qa = 3.0 * d, qb = 2.0 * c, qc = b;
  if (qa == 0.0) {
    if (qb != 0.0) visit(-qc / qb);
    return r;
  }
  const double disc = qb * qb - 4.0 * qa * qc;
  if (disc < 0.0) return r;
  const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
  visit(q / qa);
  if (q != 0.0) visit(qc / q);
  return r;
}

// The motion with one set of closed elements. The state is y = (x, x', l): the positions x
// are the gaps, and body 0's displacement where no wall fixes the row; l = (1, sin w_p t,
// cos w_p t) are the load's states, with l' = L l, so that a_g(t) is a fixed combination of
// l and y' = A y holds between contact changes. The gaps are states, not differences of
// displacements, and a stretch adds its increment (exp(A h) - I) y: so a gap is resolved to
// the round-off of its own size, not of the displacements it is made of. Without this a gap
// that drifts at 2e-6 a_p / w_p past the hysteresis threshold moved by less than an ulp of u
// per stretch, and the search for its crossing halved without end (K = 1e6, pair).
struct ContactMode {
  MatrixXd rows;      // [W; W a]: the tracked functions' values and rates from y
  VectorXd scale;     // D: lengths over L, speeds over L w (w the mode's fastest frequency)
  MatrixXd balanced;  // D a D^-1, whose exponential loses no digits to mixed scales
  double base = 0;    // the stretch length at level 0
  // Fourth derivatives, modal bound: with D a D^-1 = V diag(lambda) V^-1 and c = V^-1 D y,
  // |f_j''''(s)| <= sum_k |g_jk| |lambda_k|^4 |c_k| e^(growth s) (= modal_bound |c| e^(growth s)),
  // g = W D^-1 V, growth the largest real part if positive (a body on a negative spring; 0
  // for every physical case, whose modes decay or keep their amplitude). Each mode is charged
  // at its own frequency, so the bodies' slow motion is not charged at a stiff element's.
  bool modal = false;
  double growth = 0;
  MatrixXcd v_inv;
  MatrixXd modal_bound;
  // Near-defective pairs of modes (close eigenvalues: a critically damped element, eps = 0)
  // have large coefficients of opposite signs; for them the sum and the divided difference,
  //   g1 c1 l1^4 e^(l1 s) + g2 c2 l2^4 e^(l2 s) = (g1 c1 + g2 c2) l1^4 e^(l1 s)
  //                                              + g2 c2 (l2^4 e^(l2 s) - l1^4 e^(l1 s)),
  // |l2^4 e^(l2 s) - l1^4 e^(l1 s)| <= |l2 - l1| (4 M^3 + M^4 s e^(-sigma s)), bound what the
  // modes do together (M the larger modulus, -sigma the larger real part, times e^(growth s)
  // as above), where the modal bound alone charges each huge coefficient in full. The
  // smaller of the two is used.
  struct Pair {
    int k1, k2;
    double m, gap, reach;  // M, |l2 - l1|, max of s e^(-sigma s) over s >= 0 (1 / (e sigma))
  };
  std::vector<Pair> pairs;
  MatrixXcd g;  // W D^-1 V
  MatrixXd g_size;  // |g| kBoundMargin, and |lambda|, for the amplitude bound (amplitude_errors)
  VectorXd speed;
  // The plain bound, |f_j''''(s)| <= plain(j) exp(norm s) |D y|_inf: where modal is false;
  // norm = |D a D^-1|_inf.
  VectorXd plain;
  double norm = 0;
  // The same in the bodies' coordinates (y_b = to_bodies y), used where smaller: there a wide
  // open gap is not a large state (Pi3 = 1e4 on a record, a Jordan block and so the plain
  // bound: |D y| was the gap's 1e4 where the bodies moved by 4, and a run without a contact
  // took 1.1 million stretches instead of 76 000).
  VectorXd plain_bodies;
  double norm_bodies = 0;
  // For a gap at exactly zero (a touching start, bodies that move alike), the first of its
  // derivatives W a^p y that does not vanish decides its side (sides()): a scaled by 2^-e
  // (exactly: a power of two, so a zero stays a zero and no entry overflows when raised to
  // the 50th power), the modes' |lambda| 2^-e, and |W D^-1| summed per function.
  MatrixXd motion;
  int exponent = 0;
  VectorXd modulus, wb_size;
  // Per level: exp(a h 2^-level) - I, computed directly (not by squaring, so that each level is
  // as exact as the first) once the level has been used kCacheAfter times; how often it was.
  std::vector<MatrixXd> levels;
  std::vector<int> uses;
  // Row j: the rate of contact j's force F = -k g - c g' (the gap's row of W and the rows of
  // W a and W a^2), for a closed element; zero for an open one. Where it turns from rising to
  // falling inside a stretch, the force peaks there (peak_force).
  MatrixXd force_rate;
};

class KelvinVoigt {
 public:
  KelvinVoigt(const System& s, const Settings& set, double K)
      : s_(s),
        n_(s.n_bodies()),
        nc_(s.n_contacts()),
        nf_(s.n_contacts() + 1),
        m_(2 * s.n_bodies() + kLoadStates),
        elements_(s, compliant::Model::kelvin_voigt, K),
        K_(K),
        L_(s.length_scale()),
        slack_(1e-13 * set.tol_scale * L_),
        floor_(std::max(1e-13 * set.tol_scale * s.t_min, 8.0 * std::numeric_limits<double>::epsilon() * s.t_end)),
        cap_(set.step_cap > 0 ? set.step_cap : kDefaultStretchCap),
        deadline_(set),
        samples_(std::max(set.history_samples, 0)),
        y_(VectorXd::Zero(m_)),
        fa_(2 * nf_),
        fb_(2 * nf_),
        b4_(nf_),
        noise_(nf_),
        size_(m_),
        abs_y_(m_),
        bodies_(m_),
        body_y_(m_),
        weight_(m_),
        alt_(nf_),
        alt2_(nf_),
        term_(m_),
        sum_(m_),
        scratch_(m_),
        deriv_(m_),
        yc_(m_),
        c_(m_),
        range_(ix(nf_)),
        error_(ix(nf_)) {
    VectorXd start = VectorXd::Zero(m_);
    for (int i = 0; i < n_; ++i) {
      start(i) = s.u_start.size() == ix(n_) ? s.u_start[ix(i)] : 0.0;
      start(n_ + i) = s.v_start.size() == ix(n_) ? s.v_start[ix(i)] : 0.0;
    }
    start(2 * n_) = 1.0;  // the constant
    if (s.pulse.record) {  // a record's a_g and its slope (the load's states p, q: p' = q)
      const LoadPiece piece = s.pulse.piece(0.0);
      start(2 * n_ + 1) = piece.accel(0.0);
      start(2 * n_ + 2) = piece.slope;
    } else {
      start(2 * n_ + 2) = 1.0;  // cos(w_p t) at t = 0 (sin is 0)
    }
    // The change of coordinates: gap j = delta + u_right - u_left (and its rate), then u of
    // body 0 where there is no wall (n positions either way); the load's states as they are.
    to_gaps_ = MatrixXd::Identity(m_, m_);
    for (int half : {0, n_}) {
      to_gaps_.block(half, 0, n_, n_).setZero();
      for (int j = 0; j < nc_; ++j) {
        to_gaps_(half + j, half + s.right(j)) = 1.0;
        if (s.left(j) != kWall) to_gaps_(half + j, half + s.left(j)) = -1.0;
      }
      if (!s.wall) to_gaps_(half + nc_, half + s.ref) = 1.0;
    }
    for (int j = 0; j < nc_; ++j) to_gaps_(j, 2 * n_) = s.delta;
    to_bodies_ = to_gaps_.inverse();
    y_ = to_gaps_ * start;
    for (int k = 0; k <= kMaxLevel - kMinLevel; ++k) buf_.emplace_back(m_);
    // The tracked functions: the gaps, then u of body 0. W y is their value.
    w_ = MatrixXd::Zero(nf_, m_);
    for (int j = 0; j < nc_; ++j) w_(j, j) = 1.0;
    w_.row(nc_) = to_bodies_.row(s.ref);
    w_abs_ = w_.cwiseAbs();
    best_u_ = std::abs(w_.row(nc_).dot(y_));
    if (samples_ > 0) {
      result_.history.n_bodies = n_;
      result_.history.n_contacts = nc_;
    }
  }

  Result run() {
    const double t_pulse = s_.pulse.duration();
    ContactMode* mode = &mode_for_closed();
    record_samples(0.0, y_, *mode);
    while (t_ < s_.t_end) {
      // Stretches end at the load's breakpoints: the pulse's end, a record's every sample.
      const double stop = s_.pulse.record ? std::min(s_.pulse.next_break(t_), s_.t_end)
                          : t_ < t_pulse && t_pulse < s_.t_end ? t_pulse
                                                               : s_.t_end;
      const double t0 = t_;
      top_ = y_;
      int changed;
      if (t_ + length(*mode, level_) < stop) {
        changed = stretch(*mode, level_, 0, nullptr);
        level_ = std::clamp(level_ + (halved_ ? 1 : easy_ ? -1 : 0), kMinLevel, kMaxLevel);
      } else {  // the last stretch before the pulse's end or t_end: exactly that long
        Clip clip{stop - t_, {}, {}};
        changed = stretch(*mode, 0, 0, &clip);
        if (changed < 0) t_ = stop;  // exactly, whatever the halves summed to
      }
      record_samples(t0, top_, *mode);
      if (changed >= 0) {
        const double q = -y_(n_ + changed);
        if (elements_.closed(changed)) elements_.open(changed, q);
        else elements_.close(changed, q, t_);
        mode = &mode_for_closed();
        level_ = 0;
        ++events_;
      } else if (s_.pulse.record && t_ == stop) {
        // The next piece of the record: p = a_g (continuous, set to its sample exactly), q its
        // slope; both zero after the last sample.
        const LoadPiece piece = s_.pulse.piece(t_);
        y_(2 * n_ + 1) = piece.accel(t_);
        y_(2 * n_ + 2) = piece.slope;
      } else if (t_ == t_pulse) {
        y_(2 * n_ + 1) = y_(2 * n_ + 2) = 0.0;  // no load after the pulse
      }
      const bool finite = y_.allFinite();
      if (finite) bodies_.noalias() = to_bodies_ * y_;
      if (finite && at_rest()) {
        rest_ = t_;
        t_ = s_.t_end;
        record_samples(t_, y_, *mode, true);
        break;
      }
      std::string why;
      if (const Status end = state_end(s_, finite, bodies_.data(), bodies_.data() + n_, t_, why); end != Status::ok)
        return stopped(end, std::move(why));
      if (deadline_.tick()) return stopped(Status::time_limit, deadline_.reason() + " at t = " + std::to_string(t_));
    }
    finish();
    result_.pi1 = s_.pi1(best_u_);
    result_.t_max = t_max_;
    return std::move(result_);
  }

 private:
  static constexpr int kLoadStates = 3;

  // A stretch cut to end exactly at the pulse's end or t_end: its own exponentials.
  struct Clip {
    double h;
    std::vector<MatrixXd> levels;
    std::vector<int> uses;
  };

  static double length(const ContactMode& md, int level) { return std::ldexp(md.base, -level); }

  // exp(a h) - I, each entry to the round-off of its own size: from exp([[M, I], [0, 0]]) =
  // [[exp(M), phi1(M)], [0, I]] with M = D a D^-1 h, as M phi1(M), unbalanced.
  static MatrixXd increment(const ContactMode& md, double h) {
    const Eigen::Index m = md.balanced.rows();
    MatrixXd big = MatrixXd::Zero(2 * m, 2 * m);
    big.topLeftCorner(m, m) = md.balanced * h;
    big.topRightCorner(m, m).setIdentity();
    const MatrixXd e = big.exp();
    return md.scale.cwiseInverse().asDiagonal() * (big.topLeftCorner(m, m) * e.topRightCorner(m, m)) *
           md.scale.asDiagonal();
  }

  // The increment over a stretch of level k, (exp(a h) - I) y_, into out: by the level's matrix
  // once it is used often, else, for a short stretch, by the Taylor series of the exponential
  // on the vector (a few products with D a D^-1, where the matrix would cost an exponential
  // of twice the size: a search for a contact change visits some 45 levels once each).
  void advance(const ContactMode& md, std::vector<MatrixXd>& levels, std::vector<int>& uses, int k, double h,
               VectorXd& out) {
    if (levels[ix(k)].size() == 0 && (++uses[ix(k)] < kCacheAfter && md.norm * h <= kTaylorNorm)) {
      term_ = md.scale.cwiseProduct(y_);
      sum_.setZero();
      for (int i = 1; i <= kMaxTaylorTerms; ++i) {
        scratch_.noalias() = md.balanced * term_;
        term_ = scratch_ * (h / i);
        sum_ += term_;
        if (term_.cwiseAbs().maxCoeff() <= std::numeric_limits<double>::epsilon() * sum_.cwiseAbs().maxCoeff()) break;
      }
      out = md.scale.cwiseInverse().cwiseProduct(sum_);
      return;
    }
    if (levels[ix(k)].size() == 0) levels[ix(k)] = increment(md, h);
    out.noalias() = levels[ix(k)] * y_;
  }

  // The mode of the elements closed now, built the first time it is needed.
  ContactMode& mode_for_closed() {
    key_.assign(ix(nc_), '0');
    for (int j = 0; j < nc_; ++j)
      if (elements_.closed(j)) key_[ix(j)] = '1';
    auto [it, fresh] = modes_.try_emplace(key_);
    if (fresh) build(it->second);
    return it->second;
  }

  void build(ContactMode& md) const {
    const MatrixXd a_bodies = motion_in_bodies();
    const double w_scale = frequency_scale(a_bodies);
    const MatrixXd a = to_gaps_ * a_bodies * to_bodies_;  // in the gaps' coordinates
    const MatrixXd wb = balance(md, a, w_scale);
    plain_bounds(md, a_bodies, wb);
    const double fastest = modal_bounds(md, wb, w_scale);
    md.base = 2.0 * std::numbers::pi / std::max(fastest, s_.pulse.w) / kStretchesPerPeriod;
    md.levels.assign(ix(kMaxLevel - kMinLevel + 1), MatrixXd());
    md.uses.assign(ix(kMaxLevel - kMinLevel + 1), 0);
  }

  // The motion's matrix a (y' = a y) with the elements closed now, in the bodies' coordinates.
  MatrixXd motion_in_bodies() const {
    const int n = n_, c0 = 2 * n_, sn = c0 + 1, cs = c0 + 2;
    MatrixXd a = MatrixXd::Zero(m_, m_);

    for (int i = 0; i < n; ++i) {
      const Body& b = s_.bodies[ix(i)];
      a(i, n + i) = 1.0;
      a(n + i, i) = -b.k / b.m;
      a(n + i, n + i) = -b.c / b.m;
      if (s_.pulse.paper()) {
        a(n + i, s_.pulse.shape == PulseShape::sine ? sn : cs) = -s_.pulse.amplitude;  // -a_g(t)
      } else if (s_.pulse.record) {
        a(n + i, sn) = -1.0;  // -p
      } else {  // makris-a, -b, -c: one sinusoid s sin + c cos at w_p
        a(n + i, sn) = -s_.pulse.waves[0].s;
        a(n + i, cs) = -s_.pulse.waves[0].c;
      }
    }
    if (s_.pulse.record) {
      a(sn, cs) = 1.0;  // p' = q, q' = 0: the same matrix for every piece, only the states change
    } else {
      a(sn, cs) = s_.pulse.w;
      a(cs, sn) = -s_.pulse.w;
    }
    // A closed element pushes its right body by F = -k g - c g' and its left one by -F.
    for (int j = 0; j < nc_; ++j) {
      if (!elements_.closed(j)) continue;
      const compliant::Law& law = elements_.law(j);
      const int l = s_.left(j), r = s_.right(j);
      for (int body : {r, l}) {
        if (body == kWall) continue;
        const double sign = (body == r ? 1.0 : -1.0) / s_.bodies[ix(body)].m;
        a(n + body, r) -= sign * law.k;
        a(n + body, n + r) -= sign * law.c;
        a(n + body, c0) -= sign * law.k * s_.delta;
        if (l != kWall) {
          a(n + body, l) += sign * law.k;
          a(n + body, n + l) += sign * law.c;
        }
      }
    }
    return a;
  }

  // The frequency of the scaling D: a Gershgorin bound on the stiffness block's frequencies,
  // or the pulse's if it is faster.
  double frequency_scale(const MatrixXd& a_bodies) const {
    double w2 = 0.0;
    for (int i = 0; i < n_; ++i) w2 = std::max(w2, a_bodies.block(n_ + i, 0, 1, n_).cwiseAbs().sum());
    return std::max(s_.pulse.w, std::sqrt(w2));
  }

  // The scaling D and D a D^-1, the tracked functions' rows, the contact forces' rates, and
  // the scaled motion that decides a zero gap's side (a in the gaps' coordinates); W D^-1.
  MatrixXd balance(ContactMode& md, const MatrixXd& a, double w_scale) const {
    const int n = n_;
    VectorXd& d = md.scale;
    d = VectorXd::Ones(m_);
    d.head(n).setConstant(1.0 / L_);
    d.segment(n, n).setConstant(1.0 / (L_ * w_scale));
    md.balanced = d.asDiagonal() * a * d.cwiseInverse().asDiagonal();
    md.rows.resize(2 * nf_, m_);
    md.rows << w_, w_ * a;
    md.force_rate = MatrixXd::Zero(nc_, m_);
    for (int j = 0; j < nc_; ++j)
      if (elements_.closed(j))
        md.force_rate.row(j) = -elements_.law(j).k * md.rows.row(nf_ + j) - elements_.law(j).c * (md.rows.row(nf_ + j) * a);
    const MatrixXd wb = w_ * d.cwiseInverse().asDiagonal();  // W D^-1: functions of D y
    std::frexp(a.cwiseAbs().rowwise().sum().maxCoeff(), &md.exponent);
    md.motion = a * std::ldexp(1.0, -md.exponent);
    md.wb_size = wb.cwiseAbs().rowwise().sum();
    return wb;
  }

  // The plain bound, for where the modal one cannot be trusted.
  void plain_bounds(ContactMode& md, const MatrixXd& a_bodies, const MatrixXd& wb) const {
    const VectorXd& d = md.scale;
    const MatrixXd b2 = md.balanced * md.balanced;
    md.plain = (wb * (b2 * b2)).cwiseAbs().rowwise().sum() * kBoundMargin;
    md.norm = md.balanced.cwiseAbs().rowwise().sum().maxCoeff();
    const MatrixXd bb = d.asDiagonal() * a_bodies * d.cwiseInverse().asDiagonal(), bb2 = bb * bb;
    md.plain_bodies = ((w_ * to_gaps_ * d.cwiseInverse().asDiagonal()) * (bb2 * bb2)).cwiseAbs().rowwise().sum() * kBoundMargin;
    md.norm_bodies = bb.cwiseAbs().rowwise().sum().maxCoeff();
    md.modulus = VectorXd::Constant(m_, std::ldexp(md.norm, -md.exponent));  // the plain bound's, unless modal
  }

  // The modal bound: the eigenvectors of the whole motion, the load's states included (their
  // modes are the constant, 0, and the pulse, +-i w_p; at resonance a body's coincide with the
  // pulse's and the pair is defective: the condition number sends it to the plain bound).
  // The fastest mode's frequency, w_scale where the bound is not modal.
  double modal_bounds(ContactMode& md, const MatrixXd& wb, double w_scale) const {
    Eigen::EigenSolver<MatrixXd> eigen(md.balanced);
    if (eigen.info() != Eigen::Success) return w_scale;
    const MatrixXd blocks = eigen.pseudoEigenvalueMatrix();
    const MatrixXd basis = real_basis(eigen.pseudoEigenvectors(), blocks);
    const VectorXd norms = basis.colwise().norm().transpose();
    if (!(norms.minCoeff() > 0.0 && norms.allFinite())) return w_scale;
    const MatrixXd unit = basis * norms.cwiseInverse().asDiagonal();
    const MatrixXd unit_inv = unit.inverse();
    const double condition = unit.cwiseAbs().rowwise().sum().maxCoeff() * unit_inv.cwiseAbs().rowwise().sum().maxCoeff();
    if (!(std::isfinite(condition) && condition < kMaxModalCondition)) return w_scale;
    const MatrixXd q_of_y = norms.cwiseInverse().asDiagonal() * unit_inv;  // coefficients on the unnormalised basis
    MatrixXcd v(m_, m_);
    VectorXcd lambda(m_);
    md.v_inv.resize(m_, m_);
    const std::complex<double> i1(0.0, 1.0);
    for (int k = 0; k < m_; ++k) {
      const bool pair = k + 1 < m_ && blocks(k, k + 1) != 0.0;
      if (!pair) {
        v.col(k) = basis.col(k).cast<std::complex<double>>();
        lambda(k) = blocks(k, k);
        md.v_inv.row(k) = q_of_y.row(k).cast<std::complex<double>>();
        continue;
      }
      // Columns p1, p2 with block [[s, w], [-w, s]]: v = p1 + i p2 has lambda = s + i w,
      // and q1 p1 + q2 p2 = c v + conj(c v) with c = (q1 - i q2) / 2.
      const auto p1 = basis.col(k), p2 = basis.col(k + 1);
      v.col(k) = p1.cast<std::complex<double>>() + i1 * p2.cast<std::complex<double>>();
      v.col(k + 1) = p1.cast<std::complex<double>>() - i1 * p2.cast<std::complex<double>>();
      lambda(k) = {blocks(k, k), blocks(k, k + 1)};
      lambda(k + 1) = std::conj(lambda(k));
      md.v_inv.row(k) = 0.5 * (q_of_y.row(k).cast<std::complex<double>>() - i1 * q_of_y.row(k + 1).cast<std::complex<double>>());
      md.v_inv.row(k + 1) = md.v_inv.row(k).conjugate();
      ++k;
    }
    md.modal = true;
    md.g = wb.cast<std::complex<double>>() * v;
    md.modal_bound = md.g.cwiseAbs() * lambda.cwiseAbs2().cwiseAbs2().asDiagonal();  // |g| |lambda|^4
    md.modal_bound *= kBoundMargin;
    md.g_size = md.g.cwiseAbs() * kBoundMargin;
    md.speed = lambda.cwiseAbs();
    md.modulus = lambda.cwiseAbs() * std::ldexp(1.0, -md.exponent);
    pair_close_modes(lambda, md);
    return lambda.cwiseAbs().maxCoeff();
  }

  // The real basis (Re v, Im v of each complex pair), each column normalised on its own:
  // a pair's complex eigenvectors are nearly parallel wherever a mode moves coordinates of
  // different frequency scales (a slow mode's speeds over a stiff element's w: their
  // imaginary parts are w_slow / w_c of the real ones), so the complex V's condition grew
  // as sqrt(K) (3.6e5 at K = 1e10, 3.6e6 at 1e12 on a pair, past kMaxModalCondition: the
  // plain bound, millions of stretches). Its real and imaginary parts, turned orthogonal
  // (below) and normalised apart (modal_bounds), are not: condition 8 on that pair at
  // K = 1e10, 1e12 and 1e14. V^-1 D y is then solved in this basis and recombined per pair,
  // c = (q1 - i q2) / 2, without a sum that cancels.
  MatrixXd real_basis(MatrixXd basis, const MatrixXd& blocks) const {
    for (int k = 0; k + 1 < m_; ++k) {
      if (blocks(k, k + 1) == 0.0) continue;
      // v = p1 + i p2 times the phase e^(i phi) that makes v^T v real and positive: then
      // Re v and Im v are orthogonal (Eigen's phase is arbitrary: both parts carried the
      // slow pair's displacement, 1 and -1, and stayed parallel to 1e-5).
      const VectorXcd v = basis.col(k).cast<std::complex<double>>() + std::complex<double>(0.0, 1.0) * basis.col(k + 1);
      const VectorXcd turned = v * std::polar(1.0, -0.5 * std::arg((v.array() * v.array()).sum()));
      basis.col(k) = turned.real();
      basis.col(k + 1) = turned.imag();
      ++k;
    }
    return basis;
  }

  // Pairs each mode with its nearest unpaired neighbour when they lie within half the larger
  // modulus of each other (ContactMode::Pair; the bound takes the smaller of alone and together).
  static void pair_close_modes(const VectorXcd& lambda, ContactMode& md) {
    const int m = static_cast<int>(lambda.size());
    std::vector<char> paired(ix(m), 0);
    for (int k = 0; k < m; ++k) {
      if (paired[ix(k)]) continue;
      int best = -1;
      for (int q = k + 1; q < m; ++q)
        if (!paired[ix(q)] && (best < 0 || std::abs(lambda(q) - lambda(k)) < std::abs(lambda(best) - lambda(k))))
          best = q;
      if (best < 0) continue;
      const double big = std::max(std::abs(lambda(k)), std::abs(lambda(best)));
      const double gap = std::abs(lambda(best) - lambda(k));
      if (gap > 0.5 * big) continue;
      const double sigma = -std::max(lambda(k).real(), lambda(best).real());
      paired[ix(k)] = paired[ix(best)] = 1;
      md.pairs.push_back({k, best, big, gap,
                          sigma > 0.0 ? 1.0 / (std::numbers::e * sigma) : std::numeric_limits<double>::infinity()});
    }
    md.growth = std::max(0.0, lambda.real().maxCoeff());
  }

  // The fourth-derivative bounds of the tracked functions over [t_, t_ + h], into b4_.
  void fourth_bounds(const ContactMode& md, double h) {
    if (md.modal) {
      yc_ = md.scale.cwiseProduct(y_).cast<std::complex<double>>();
      c_.noalias() = md.v_inv * yc_;
      size_ = c_.cwiseAbs();
      b4_.noalias() = md.modal_bound * size_;
      for (const ContactMode::Pair& pr : md.pairs) {
        const double m3 = pr.m * pr.m * pr.m, tail = pr.gap * (4.0 * m3 + m3 * pr.m * std::min(h, pr.reach));
        for (int j = 0; j < nf_; ++j) {
          const std::complex<double> one = md.g(j, pr.k1) * c_(pr.k1), two = md.g(j, pr.k2) * c_(pr.k2);
          const double alone = md.modal_bound(j, pr.k1) * size_(pr.k1) + md.modal_bound(j, pr.k2) * size_(pr.k2);
          const double together = kBoundMargin * (std::abs(one + two) * m3 * pr.m + std::abs(two) * tail);
          if (together < alone) b4_(j) += together - alone;
        }
      }
      if (md.growth > 0.0) b4_ *= std::exp(md.growth * h);
    } else {
      b4_ = md.plain * (std::exp(md.norm * h) * md.scale.cwiseProduct(y_).cwiseAbs().maxCoeff());
      body_y_.noalias() = to_bodies_ * y_;
      b4_ = b4_.cwiseMin(md.plain_bodies * (std::exp(md.norm_bodies * h) * md.scale.cwiseProduct(body_y_).cwiseAbs().maxCoeff()));
    }
  }

  // A second bound on |f_j - H| over [t_, t_ + h] for every tracked function, into out
  // (after fourth_bounds: size_): mode by mode the smaller of the Hermite charge
  // |g c| |lambda|^4 h^4 / 384 and |f_k| + |H_k| <= |g c| (2 + (8/27) |lambda| h) (|h00| + |h01|
  // = 1, |h10|, |h11| <= 4/27), times e^(growth h). A stiff element's mode, once damped out,
  // keeps a coefficient of the eigenvectors' round-off (1e-15 of the state at K = 1e12: the
  // inverse's small entries are known to an ulp of its large ones), which the Hermite charge
  // multiplied by |lambda|^4 (2.5e23): a pair pressed together for seconds with a gap of -1e-12
  // took 2e5 stretches of 1.8e-5. Charged at its amplitude it no longer shortens the stretch.
  void amplitude_errors(const ContactMode& md, double h, VectorXd& out) {
    if (!md.modal) {
      out.setConstant(std::numeric_limits<double>::infinity());
      return;
    }
    const double h4 = h * h * h * h / 384.0;
    for (int k = 0; k < m_; ++k) {
      const double l = md.speed(k);
      weight_(k) = size_(k) * std::min(l * l * l * l * h4, 2.0 + (8.0 / 27.0) * l * h);
    }
    out.noalias() = md.g_size * weight_;
    out *= std::exp(md.growth * h);
  }

  enum class Verdict { unproven, proven, proven_with_room };

  // Whether the gap of contact j, exactly zero at t_, keeps to its element's side over
  // [t_, t_ + h] (open: not below zero; closed: not above), decided by its first derivative
  // f^(p) = W a^p y that does not vanish, as the rigid reference decides a touching start
  // (DERIVATION.md §8). Past it, f(s) = f^(p) s^p / p! + R with |R| <= B s^(p+1) / (p+1)!, B a
  // bound on |f^(p+1)| over the stretch (modal or plain, as b4 is for p = 3), so f keeps the
  // sign of f^(p) while s B / (p + 1) < |f^(p)|. If W a^p y vanishes for every p < m, it does for
  // every p (Cayley-Hamilton): the gap is zero throughout, and its element changes neither way
  // (each acts while its gap is strictly negative). The Hermite tests cannot see either: a gap
  // identically zero is never proven positive, and one that starts as s^5 (bodies of unequal
  // frequency at rest, a sine pulse) has a negative interpolant near zero. After
  // fourth_bounds(md, h) (c_, size_).
  Verdict sides(const ContactMode& md, int j, double h) {
    const double side = elements_.closed(j) ? -1.0 : 1.0;
    deriv_ = y_;
    for (int p = 1; p < m_; ++p) {
      scratch_.noalias() = md.motion * deriv_;
      deriv_.swap(scratch_);
      const double d = side * deriv_(j);  // f^(p) 2^(-e p): W's row j picks gap j
      if (d == 0.0) continue;
      if (!(d > 0.0)) return Verdict::unproven;
      double b = 0.0;  // B 2^(-e (p + 1))
      if (md.modal) {
        for (int k = 0; k < m_; ++k) b += std::abs(md.g(j, k)) * std::pow(md.modulus(k), p + 1) * size_(k);
        b *= kBoundMargin * std::exp(md.growth * h);
      } else {
        b = kBoundMargin * md.wb_size(j) * std::pow(md.modulus(0), p + 1) * std::exp(md.norm * h) *
            md.scale.cwiseProduct(y_).cwiseAbs().maxCoeff();
      }
      const double need = b * std::ldexp(h, md.exponent) / (p + 1);
      return kEasyRoom * need < d ? Verdict::proven_with_room : need < d ? Verdict::proven : Verdict::unproven;
    }
    return Verdict::proven_with_room;
  }

  // Where the Hermite tests fail: true if gap j is at zero and sides() proves it (room
  // updated), false to halve.
  bool at_zero_keeps_side(const ContactMode& md, int j, double h, bool& room) {
    if (fa_(j) != 0.0) return false;
    const Verdict side = sides(md, j, h);
    room = room && side == Verdict::proven_with_room;
    return side != Verdict::unproven;
  }

  // Whether contact j's element should change at state y: its gap has crossed zero. Each
  // element acts exactly while its gap is negative: a band of hysteresis of width tol would
  // let the dashpot push or pull c tol too long at every change (6.5e-11 of Pi1 measured at
  // K = 1e6 with tol = 1e-12 a_p / w_p^2).
  int first_change(const VectorXd& y) const {
    for (int j = 0; j < nc_; ++j)
      if (elements_.closed(j) ? y(j) > 0.0 : y(j) < 0.0) return j;
    return -1;
  }

  // Judges [t_, t_ + h] from y_ to yb: proven when no element changes in it, and |u0| and
  // every penetration are either below what was seen or known to within the slack there.
  // A gap's sign is proven by the uniform bound |f - H| <= b4 h^4 / 384, or, for a gap that
  // starts at zero (just after its element changed), by the pointwise one b4 s^2 (h - s)^2 / 24
  // <= (b4 h^2 / 24) s^2, which vanishes at the start. Each test allows for the round-off of
  // the function's own evaluation, else a function that hovers at its threshold to within it
  // would be halved down to the floor over its whole length.
  Verdict judge(const ContactMode& md, double h, const VectorXd& yb) {
    fa_.noalias() = md.rows * y_;
    fb_.noalias() = md.rows * yb;
    fourth_bounds(md, h);
    amplitude_errors(md, h, alt_);
    amplitude_errors(md, 2.0 * h, alt2_);
    abs_y_ = y_.cwiseAbs();
    noise_.noalias() = w_abs_ * abs_y_;
    const double h4 = h * h * h * h / 384.0;
    bool room = true;
    for (int j = 0; j < nf_; ++j) {
      const Range r = hermite_range(fa_(j), fa_(nf_ + j), fb_(j), fb_(nf_ + j), h);
      const double e = std::min(b4_(j) * h4, alt_(j)), noise = kNoise * noise_(j);
      // The error at twice the length, for the room to double: 16 e for the Hermite charge, at
      // most 2 e where the amplitude bound is the smaller (which grows about as h).
      const double e2 = std::min(kEasyRoom * b4_(j) * h4, alt2_(j));
      range_[ix(j)] = r;
      error_[ix(j)] = e;
      if (!(e < std::numeric_limits<double>::infinity())) return Verdict::unproven;
      const double bend = b4_(j) * h * h / 24.0;
      if (j == nc_) {  // u0
        const double top = std::max(r.hi, -r.lo), slack = std::max(slack_, noise);
        if (e > slack && top + e > best_u_ + slack) return Verdict::unproven;
        room = room && (e2 <= slack || top + e2 <= best_u_ + slack);
      } else if (!elements_.closed(j)) {
        if (r.lo - e + noise <= 0.0 &&
            hermite_range(fa_(j), fa_(nf_ + j), fb_(j), fb_(nf_ + j), h, -bend).lo + noise <= 0.0) {
          if (!at_zero_keeps_side(md, j, h, room)) return Verdict::unproven;
        } else {
          room = room && r.lo - e2 > 0.0;
        }
      } else {
        if (r.hi + e - noise >= 0.0 &&
            hermite_range(fa_(j), fa_(nf_ + j), fb_(j), fb_(nf_ + j), h, bend).hi - noise >= 0.0) {
          if (!at_zero_keeps_side(md, j, h, room)) return Verdict::unproven;
        }
        const double slack = std::max({slack_, 1e-9 * -min_gap_, noise});
        if (e > slack && r.lo - e < min_gap_ - slack) return Verdict::unproven;
        room = room && r.hi + e2 < 0.0 && (e2 <= slack || r.lo - e2 >= min_gap_ - slack);
      }
    }
    return room ? Verdict::proven_with_room : Verdict::proven;
  }

  // The largest force of closed contact j inside [t_, t_ + h] from y_ to yb, located (issue 48):
  // where its rate falls from positive to negative, the rate's root, bisected on the exact
  // motion y_ + (exp(a s) - I) y_ to h 2^-40 (the force is flat there: its value is then
  // F'' (h 2^-40)^2 / 2 from the peak's, far below round-off); 0 where the force does not peak
  // inside. An exponential a halving, once per contact's peak.
  double peak_force(const ContactMode& md, int j, const VectorXd& yb, double h) const {
    if (!(md.force_rate.row(j).dot(y_) > 0.0 && md.force_rate.row(j).dot(yb) < 0.0)) return 0.0;
    double lo = 0.0, hi = h;
    VectorXd y = yb;
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (lo + hi);
      y = y_ + increment(md, mid) * y_;
      (md.force_rate.row(j).dot(y) > 0.0 ? lo : hi) = mid;
    }
    return elements_.law(j).force(-y(j), -y(n_ + j), elements_.v_minus(j));
  }

  // The stretch from t_ to t_ + h is taken: its extremes are those of the Hermite ranges
  // where judged (within the slack), else its end's; each contact's force at its end and at
  // a peak inside it.
  void take(const ContactMode& md, const VectorXd& yb, double h, bool judged) {
    if (judged) {
      const Range& u = range_[ix(nc_)];
      if (error_[ix(nc_)] <= std::max(slack_, kNoise * noise_(nc_))) {
        if (u.hi > best_u_) best_u_ = u.hi, t_max_ = t_ + u.t_hi;
        if (-u.lo > best_u_) best_u_ = -u.lo, t_max_ = t_ + u.t_lo;
      }
      for (int j = 0; j < nc_; ++j)
        if (elements_.closed(j) && error_[ix(j)] <= std::max({slack_, 1e-9 * -min_gap_, kNoise * noise_(j)}))
          min_gap_ = std::min(min_gap_, range_[ix(j)].lo);
    }
    const double u = std::abs(w_.row(nc_).dot(yb));
    if (u > best_u_) best_u_ = u, t_max_ = t_ + h;
    for (int j = 0; j < nc_; ++j)
      if (elements_.closed(j)) {
        min_gap_ = std::min(min_gap_, w_.row(j).dot(yb));
        // The element's force from its gap and rate (the state's first 2 nc_ coordinates).
        force_max_ = std::max({force_max_, elements_.law(j).force(-yb(j), -yb(n_ + j), elements_.v_minus(j)),
                               peak_force(md, j, yb, h)});
      }
    y_ = yb;
    t_ += h;
  }

  // Advances y_, t_ over the stretch of `level` from t_ and returns -1, or stops at the first
  // element change and returns its contact. A stretch that is not proven is halved; at the
  // floor, a change at its end is located, and a stretch without one is a graze.
  int stretch(ContactMode& md, int level, int depth, Clip* clip) {
    if (deadline_.tick()) throw OutOfTime{};
    const double h = clip ? std::ldexp(clip->h, -level) : length(md, level);
    VectorXd& yb = buf_[ix(depth)];
    if (clip) {
      if (clip->levels.size() <= ix(level)) clip->levels.resize(ix(level) + 1), clip->uses.resize(ix(level) + 1);
      advance(md, clip->levels, clip->uses, level, h, yb);
    } else {
      advance(md, md.levels, md.uses, level - kMinLevel, h, yb);
    }
    yb += y_;
    if (++stretches_ > cap_) throw OutOfSteps{};
    const int change = first_change(yb);
    const Verdict verdict = change < 0 ? judge(md, h, yb) : Verdict::unproven;
    if (verdict != Verdict::unproven || h <= floor_ || level >= kMaxLevel || ix(depth + 1) >= buf_.size()) {
      take(md, yb, h, verdict != Verdict::unproven);
      if (depth == 0) halved_ = false, easy_ = verdict == Verdict::proven_with_room;
      return change;
    }
    if (depth == 0) halved_ = true, easy_ = false;
    const int first = stretch(md, level + 1, depth + 1, clip);
    return first >= 0 ? first : stretch(md, level + 1, depth + 1, clip);
  }

  // Whether the bodies are at rest to within kAtRest of the pulse's scales with no load left
  // (DERIVATION.md §8). On a touching wall with eps = 0 at K >= 1e10 the gap decays under a
  // critically damped element into denormals and stops at a floating-point fixed point (gap
  // -4.9e-324, rate 9.8e-320) that no stretch longer than 1.6e-5 can prove negative: 2 s of
  // wall time reached t = 14 of 33 (K = 1e10). From there the motion is a decaying linear
  // one of that size: it cannot change Pi1, the deepest penetration or an impact's speed.
  bool at_rest() const {
    if (t_ < s_.pulse.duration() || y_(2 * n_ + 1) != 0.0 || y_(2 * n_ + 2) != 0.0) return false;
    return bodies_.head(n_).cwiseAbs().maxCoeff() <= kAtRest * L_ &&
           bodies_.segment(n_, n_).cwiseAbs().maxCoeff() <= kAtRest * L_ * s_.pulse.w;
  }

  // History rows at the sample times in (t0, t_] (and t = 0), from the state y0 at t0 (held
  // there at rest).
  void record_samples(double t0, const VectorXd& y0, const ContactMode& md, bool hold = false) {
    auto& rows = result_.history.data;
    while (next_sample_ < samples_) {
      const double ts = samples_ > 1 ? s_.t_end * next_sample_ / (samples_ - 1) : 0.0;
      if (ts > t_) break;
      ++next_sample_;
      const VectorXd y = hold ? y0 : VectorXd(y0 + increment(md, ts - t0) * y0);
      const VectorXd bodies = to_bodies_ * y;
      rows.push_back(ts);
      for (int i = 0; i < 2 * n_; ++i) rows.push_back(bodies(i));
      for (int j = 0; j < nc_; ++j) rows.push_back(y(j));
      for (int j = 0; j < nc_; ++j) rows.push_back(elements_.force(j, bodies.data(), bodies.data() + n_));
    }
  }

  // steps counts the stretches (the work, as CVODE's steps count its own); the message, the
  // contact changes (the rigid reference's events).
  void finish() {
    result_.steps = stretches_;
    result_.impacts = elements_.impacts();
    result_.min_gap = min_gap_ < 0.0 ? min_gap_ : std::numeric_limits<double>::infinity();
    result_.contact_force_max = force_max_;
    elements_.finish(result_);
    result_.message = std::to_string(events_) + " contact changes";
    if (rest_ >= 0.0) result_.message += "; at rest (below 1e-200 a_p/w_p^2) from t = " + std::to_string(rest_);
    if (K_ > kMostVouchedStiffness) {
      result_.doubt = "K above 1e12: a pressed contact's gap (-F/K) nears the state's round-off and its sign "
                      "may be round-off (impacts that change with --tol-scale; DERIVATION.md section 8)";
      result_.message += "; " + result_.doubt;
    }
  }

  Result stopped(Status status, std::string message) {
    finish();
    result_.status = status;
    result_.message = std::move(message);
    return std::move(result_);
  }

 public:
  struct OutOfTime {};
  struct OutOfSteps {};
  Result out_of_time() { return stopped(Status::time_limit, deadline_.reason() + " at t = " + std::to_string(t_)); }
  Result out_of_steps() {
    return stopped(Status::step_cap, "more than " + std::to_string(cap_) + " stretches at t = " + std::to_string(t_));
  }

 private:
  const System& s_;
  const int n_, nc_, nf_, m_;
  compliant::Elements elements_;
  const double K_;
  const double L_, slack_, floor_;
  const long cap_;
  Deadline deadline_;
  const int samples_;
  int next_sample_ = 0;
  VectorXd y_, top_;
  MatrixXd to_gaps_, to_bodies_;  // bodies' coordinates to the gaps', and back
  MatrixXd w_, w_abs_;
  // Scratch, sized once: judging a stretch allocates nothing.
  VectorXd fa_, fb_, b4_, noise_, size_, abs_y_, bodies_, body_y_, weight_, alt_, alt2_, term_, sum_, scratch_, deriv_;
  VectorXcd yc_, c_;
  std::vector<Range> range_;
  std::vector<double> error_;
  std::vector<VectorXd> buf_;
  std::map<std::string, ContactMode> modes_;
  std::string key_;
  int level_ = 0;
  bool halved_ = false, easy_ = false;
  double rest_ = -1.0;  // when the bodies came to rest (at_rest()), or -1
  double t_ = 0.0, t_max_ = 0.0, best_u_ = 0.0, min_gap_ = 0.0, force_max_ = 0.0;
  long events_ = 0, stretches_ = 0;
  Result result_;
};

}  // namespace

Result solve_kelvin_voigt(const System& system, const Settings& settings) {
  Result r;
  r.status = Status::failed;
  for (const Body& b : system.bodies)
    if (!(b.m > 0.0 && std::isfinite(b.m) && std::isfinite(b.k) && std::isfinite(b.c))) {
      r.message = "every body needs a finite positive mass and a finite spring and dashpot";
      return r;
    }
  if (system.pulse.shape == PulseShape::mp) {
    r.message = "the Kelvin-Voigt reference takes the paper's pulses, makris-a, -b, -c and records; the mp pulse's "
                "three frequencies would need seven load states (not built): use the compliant solver's cvode";
    return r;
  }
  if (system.n_bodies() > kMaxKelvinVoigtBodies) {
    r.message = "the Kelvin-Voigt reference holds the whole state in one matrix: at most " +
                std::to_string(kMaxKelvinVoigtBodies) + " bodies, not " + std::to_string(system.n_bodies());
    return r;
  }
  try {
    const double K = settings.stiffness > 0.0 ? settings.stiffness : compliant::kDefaultStiffness;
    KelvinVoigt solver(system, settings, K);
    try {
      return solver.run();
    } catch (const KelvinVoigt::OutOfTime&) {
      return solver.out_of_time();
    } catch (const KelvinVoigt::OutOfSteps&) {
      return solver.out_of_steps();
    }
  } catch (const std::exception& e) {
    r.message = e.what();
    return r;
  }
}

}  // namespace pb::event_driven
