// The buildings' exact reference (solvers/buildings_reference/) against independent
// computations: the matrix exponential of the whole linear system (no contact, and the stuck
// system's closed form), the single oscillators' reference (one storey each); and its own
// exact properties: self-similarity, the energy balance.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include "cases/buildings.hpp"
#include "cases/record.hpp"
#include "cases/system.hpp"
#include "solvers/buildings_reference/motion.hpp"
#include "solvers/buildings_reference/reference.hpp"
#include "solvers/buildings_reference/stuck.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "kit/testing_buildings.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace buildings_reference_tests {

using test::building;
using test::issue_scene;

// The whole linear system without contact, y = (u, v), advanced by the matrix exponential of
// its first-order form augmented with the load's states (1, s, and sin, cos of each sinusoid),
// piece by piece of the load: no modes, no closed form of ours. Peaks from the samples and the
// cubic Hermite interpolant of u and its rate between them (error h^4 max|u^(4)| / 384).
struct Independent {
  std::vector<double> floor_peak, drift_peak;
};

// The largest |cubic| on [0, h] through (f0, d0), (f1, d1).
double cubic_max(double f0, double d0, double f1, double d1, double h) {
  const double c1 = h * d0, c2 = 3.0 * (f1 - f0) - h * (2.0 * d0 + d1), c3 = 2.0 * (f0 - f1) + h * (d0 + d1);
  double best = std::max(std::abs(f0), std::abs(f1));
  const double qa = 3.0 * c3, qb = 2.0 * c2, qc = c1;
  const double disc = qb * qb - 4.0 * qa * qc;
  if (std::abs(qa) > 0.0 && disc >= 0.0) {
    for (double sgn : {-1.0, 1.0}) {
      const double s = (-qb + sgn * std::sqrt(disc)) / (2.0 * qa);
      if (s > 0.0 && s < 1.0) best = std::max(best, std::abs(f0 + s * (c1 + s * (c2 + s * c3))));
    }
  }
  return best;
}

double drift_of(const BuildingModel& md, int i, const Eigen::VectorXd& x) {
  const bool bottom = md.first[static_cast<std::size_t>(md.building_of[static_cast<std::size_t>(i)])] == i;
  return bottom ? x(i) : x(i) - x(i - 1);
}

Independent integrate_without_contact(const BuildingModel& md, int steps_per_period) {
  const int n = md.n_floors;
  const Eigen::VectorXd minv = md.m.cwiseInverse();
  const Pulse& pulse = md.scene.pulse;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n);
  Independent out;
  out.floor_peak.assign(static_cast<std::size_t>(n), 0.0);
  out.drift_peak.assign(static_cast<std::size_t>(n), 0.0);
  double t = 0.0;
  const double h_target = md.t_min / steps_per_period;
  while (t < md.t_end) {
    const LoadPiece piece = pulse.piece(t);
    const double end = std::min(piece.end, md.t_end);
    const int nw = piece.n_waves;
    const int nl = 2 + 2 * nw;  // 1, s, then (sin, cos) per wave
    const int dim = 2 * n + nl;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(dim, dim);
    a.block(0, n, n, n).setIdentity();
    a.block(n, 0, n, n) = -(minv.asDiagonal() * md.K);
    a.block(n, n, n, n) = -(minv.asDiagonal() * md.C);
    // v' gets -a_g, a_g = value + slope s + sum (ps sin + pc cos).
    const int l0 = 2 * n;
    a.block(n, l0, n, 1).setConstant(-(piece.value + piece.slope * (t - piece.start)));
    a.block(n, l0 + 1, n, 1).setConstant(-piece.slope);
    a(l0 + 1, l0) = 1.0;  // s' = 1
    for (int j = 0; j < nw; ++j) {
      const Sinusoid& w = piece.waves[static_cast<std::size_t>(j)];
      const int js = l0 + 2 + 2 * j;
      a.block(n, js, n, 1).setConstant(-w.s);
      a.block(n, js + 1, n, 1).setConstant(-w.c);
      a(js, js + 1) = w.w;   // sin' = w cos
      a(js + 1, js) = -w.w;  // cos' = -w sin
    }
    const int steps = std::max(1, static_cast<int>(std::ceil((end - t) / h_target)));
    const double h = (end - t) / steps;
    const Eigen::MatrixXd e = (a * h).exp();
    Eigen::VectorXd x(dim);
    x.head(2 * n) = y;
    x(l0) = 1.0;
    x(l0 + 1) = 0.0;
    for (int j = 0; j < nw; ++j) {
      const Sinusoid& w = piece.waves[static_cast<std::size_t>(j)];
      x(l0 + 2 + 2 * j) = std::sin(w.w * t);
      x(l0 + 3 + 2 * j) = std::cos(w.w * t);
    }
    for (int k = 0; k < steps; ++k) {
      const Eigen::VectorXd next = e * x;
      const Eigen::VectorXd u0 = x.head(n), v0 = x.segment(n, n), u1 = next.head(n), v1 = next.segment(n, n);
      for (int i = 0; i < n; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        out.floor_peak[ii] = std::max(out.floor_peak[ii], cubic_max(u0(i), v0(i), u1(i), v1(i), h));
        out.drift_peak[ii] = std::max(out.drift_peak[ii], cubic_max(drift_of(md, i, u0), drift_of(md, i, v0),
                                                                    drift_of(md, i, u1), drift_of(md, i, v1), h));
      }
      x = next;
    }
    y = x.head(2 * n);
    t = end;
  }
  return out;
}

void expect_peaks_of(const BuildingModel& md, const buildings::BuildingsResult& r, const Independent& ind, double tol) {
  for (std::size_t b = 0; b < md.scene.buildings.size(); ++b)
    for (int f = 1; f <= md.scene.buildings[b].floors(); ++f) {
      const auto i = static_cast<std::size_t>(md.global(static_cast<int>(b), f));
      const auto k = static_cast<std::size_t>(f - 1);
      EXPECT_NEAR(r.floor_peak[b][k] / ind.floor_peak[i], 1.0, tol) << "building " << b << ", floor " << f;
      EXPECT_NEAR(r.drift_peak[b][k] / ind.drift_peak[i], 1.0, tol) << "building " << b << ", storey " << f;
    }
}

TEST(BuildingsReference, NoContactIsTheMatrixExponentialsMotion) {
  BuildingScene s = issue_scene();
  s.no_contact = true;
  const BuildingModel md = assemble(s);
  const buildings::BuildingsResult r = buildings::solve(md);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  expect_peaks_of(md, r, integrate_without_contact(md, 2000), 1e-11);
  EXPECT_EQ(r.events, 2);  // the pulse's end, t_end
  EXPECT_EQ(r.contacts.size(), 0u);
}

TEST(BuildingsReference, NoContactAtResonanceIsTheMatrixExponentialsMotion) {
  // Undamped, the pulse at building 0's second mode exactly: the secular branch (t sin, t cos).
  BuildingScene s = issue_scene();
  s.no_contact = true;
  s.xi = 0.0;
  s.pulse = Pulse(PulseShape::sine, 3.0, building_modes(s.buildings[0]).w(1));
  const BuildingModel md = assemble(s);
  const buildings::BuildingsResult r = buildings::solve(md);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  expect_peaks_of(md, r, integrate_without_contact(md, 2000), 1e-11);
}

TEST(BuildingsReference, NoContactWithOverdampedModesIsTheMatrixExponentialsMotion) {
  // Rayleigh's ratio grows with the mode: xi = 0.6 in modes 1 and 2 leaves the upper modes of
  // a six-storey building overdamped (real roots).
  BuildingScene s = issue_scene();
  s.no_contact = true;
  s.xi = 0.6;
  s.buildings[1] = uniform_building(6, 2e5, 10.0);
  const BuildingModel md = assemble(s);
  ASSERT_GT(md.modes[1].xi(5), 1.0);
  const buildings::BuildingsResult r = buildings::solve(md);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  expect_peaks_of(md, r, integrate_without_contact(md, 2000), 1e-11);
}

TEST(BuildingsReference, NoContactOfThreeModallyDampedBuildingsUnderARecordIsTheMatrixExponentialsMotion) {
  BuildingScene s = issue_scene();
  s.no_contact = true;
  s.damping = BuildingDamping::modal;
  s.xi = 0.03;
  s.buildings.push_back(building({1e5, 1.2e5, 0.9e5, 1e5}, {1.5e8, 1.4e8, 1.1e8, 0.9e8}));
  auto rec = std::make_shared<Record>();
  rec->source = "synthetic";
  for (int i = 0; i <= 60; ++i) {
    rec->t.push_back(0.01 * i);
    rec->a.push_back(i == 0 || i == 60 ? 0.0 : 2.0 * std::sin(0.37 * i) + 0.5 * std::cos(1.3 * i));
    rec->peak = std::max(rec->peak, std::abs(rec->a.back()));
  }
  s.pulse = Pulse{};
  s.pulse.shape = PulseShape::record;
  s.pulse.amplitude = -1.0;  // reverse
  s.pulse.w = 10.0;
  s.pulse.record = rec;
  const BuildingModel md = assemble(s);
  const buildings::BuildingsResult r = buildings::solve(md);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_GE(r.events, 60);  // one a sample
  expect_peaks_of(md, r, integrate_without_contact(md, 2000), 1e-11);
}

// Pounding without floors that stick, integrated independently: the whole system by the matrix
// exponential on steps of t_min / steps_per_period, every gap sampled at every step end and a
// closure located by bisection on the exponential (to 1e-15 of t_end), Newton's impact of the
// one contact closing, and the peaks as integrate_without_contact takes them. Sampling could
// step over a grazing closure; the scenes below have none (their impacts approach at over
// 1e-3 a_p / w_p), and none sticks (asserted). They agree within 5.3e-12 (the bisection's and
// the exponential's round-off), with the same impacts.
struct Pounding {
  std::vector<double> floor_peak, drift_peak;
  std::vector<long> impacts;
  std::vector<double> first_impact, fastest;
};

Pounding integrate_pounding(const BuildingModel& md, int steps_per_period) {
  const int n = md.n_floors, nc = static_cast<int>(md.contacts.size());
  const Eigen::VectorXd minv = md.m.cwiseInverse();
  const Pulse& pulse = md.scene.pulse;
  Pounding out;
  out.floor_peak.assign(static_cast<std::size_t>(n), 0.0);
  out.drift_peak.assign(static_cast<std::size_t>(n), 0.0);
  out.impacts.assign(static_cast<std::size_t>(nc), 0);
  out.first_impact.assign(static_cast<std::size_t>(nc), std::numeric_limits<double>::quiet_NaN());
  out.fastest.assign(static_cast<std::size_t>(nc), 0.0);
  const auto gap = [&](const Eigen::VectorXd& x, int j) {
    const FloorContact& c = md.contacts[static_cast<std::size_t>(j)];
    return md.scene.delta + x(c.i_right) - x(c.i_left);
  };
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n);
  double t = 0.0;
  const double h_target = md.t_min / steps_per_period;
  while (t < md.t_end) {
    const LoadPiece piece = pulse.piece(t);
    const double end = std::min(piece.end, md.t_end);
    const int nw = piece.n_waves, l0 = 2 * n, dim = 2 * n + 2 + 2 * nw;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(dim, dim);
    a.block(0, n, n, n).setIdentity();
    a.block(n, 0, n, n) = -(minv.asDiagonal() * md.K);
    a.block(n, n, n, n) = -(minv.asDiagonal() * md.C);
    a.block(n, l0, n, 1).setConstant(-(piece.value + piece.slope * (t - piece.start)));
    a.block(n, l0 + 1, n, 1).setConstant(-piece.slope);
    a(l0 + 1, l0) = 1.0;
    for (int j = 0; j < nw; ++j) {
      const Sinusoid& w = piece.waves[static_cast<std::size_t>(j)];
      const int js = l0 + 2 + 2 * j;
      a.block(n, js, n, 1).setConstant(-w.s);
      a.block(n, js + 1, n, 1).setConstant(-w.c);
      a(js, js + 1) = w.w;
      a(js + 1, js) = -w.w;
    }
    // The augmented state at the piece's start.
    Eigen::VectorXd x(dim);
    x.head(2 * n) = y;
    x(l0) = 1.0;
    x(l0 + 1) = 0.0;
    for (int j = 0; j < nw; ++j) {
      const Sinusoid& w = piece.waves[static_cast<std::size_t>(j)];
      x(l0 + 2 + 2 * j) = std::sin(w.w * t);
      x(l0 + 3 + 2 * j) = std::cos(w.w * t);
    }
    const int steps = std::max(1, static_cast<int>(std::ceil((end - t) / h_target)));
    const double h = (end - t) / steps;
    const Eigen::MatrixXd e = (a * h).exp();
    double tk = t;
    while (tk < end) {
      const double step = std::min(h, end - tk);
      Eigen::VectorXd next = step == h ? Eigen::VectorXd(e * x) : Eigen::VectorXd((a * step).exp() * x);
      double t_next = tk + step;
      // The first contact whose gap is negative at the step's end: bisect for its closure.
      int which = -1;
      for (int j = 0; j < nc; ++j)
        if (gap(next, j) < 0.0) {
          double lo = 0.0, hi = step;
          while (hi - lo > 1e-15 * md.t_end) {
            const double mid = 0.5 * (lo + hi);
            const Eigen::VectorXd xm = (a * mid).exp() * x;
            (gap(xm, j) < 0.0 ? hi : lo) = mid;
          }
          if (which < 0 || tk + hi < t_next) {
            which = j;
            t_next = tk + hi;
            next = (a * hi).exp() * x;
          }
        }
      const double dt = t_next - tk;
      const Eigen::VectorXd u0 = x.head(n), v0 = x.segment(n, n), u1 = next.head(n), v1 = next.segment(n, n);
      for (int i = 0; i < n; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        out.floor_peak[ii] = std::max(out.floor_peak[ii], cubic_max(u0(i), v0(i), u1(i), v1(i), dt));
        out.drift_peak[ii] = std::max(out.drift_peak[ii], cubic_max(drift_of(md, i, u0), drift_of(md, i, v0),
                                                                    drift_of(md, i, u1), drift_of(md, i, v1), dt));
      }
      x = next;
      tk = t_next;
      if (which >= 0) {
        const FloorContact& c = md.contacts[static_cast<std::size_t>(which)];
        const double rate = x(n + c.i_right) - x(n + c.i_left);
        EXPECT_LT(rate, -1e-3 * md.speed_scale()) << "a graze at t = " << tk;
        const double lambda = -(1.0 + md.scene.eps) * rate / (minv(c.i_left) + minv(c.i_right));
        x(n + c.i_left) -= lambda * minv(c.i_left);
        x(n + c.i_right) += lambda * minv(c.i_right);
        const auto k = static_cast<std::size_t>(which);
        ++out.impacts[k];
        if (std::isnan(out.first_impact[k])) out.first_impact[k] = tk;
        out.fastest[k] = std::max(out.fastest[k], -rate);
      }
    }
    y = x.head(2 * n);
    t = end;
  }
  return out;
}

TEST(BuildingsReference, PoundingWithoutStickingIsTheMatrixExponentialsWithBisectedClosures) {
  int scenes = 0;
  for (double gap : {0.02, 0.03})
    for (double eps : {0.6, 1.0})
      for (int three : {0, 1}) {
        BuildingScene s = issue_scene();
        s.delta = gap;
        s.eps = eps;
        if (three) s.buildings.push_back(building({1e5, 1.2e5, 1.1e5, 0.9e5}, {1.5e8, 1.4e8, 1.2e8, 1.0e8}));
        const BuildingModel md = assemble(s);
        const buildings::BuildingsResult r = buildings::solve(md);
        ASSERT_EQ(r.status, Status::ok) << r.message;
        long impacts = 0;
        for (const buildings::ContactResult& c : r.contacts) {
          ASSERT_EQ(c.contact_phases, 0) << "gap " << gap << " eps " << eps;
          impacts += c.impacts;
        }
        if (impacts == 0) continue;
        ++scenes;
        const Pounding ind = integrate_pounding(md, 1000);
        const std::string at = "gap " + std::to_string(gap) + " eps " + std::to_string(eps) + " buildings " +
                               std::to_string(s.buildings.size());
        for (std::size_t b = 0; b < s.buildings.size(); ++b)
          for (int f = 1; f <= s.buildings[b].floors(); ++f) {
            const auto i = static_cast<std::size_t>(md.global(static_cast<int>(b), f));
            const auto k = static_cast<std::size_t>(f - 1);
            EXPECT_NEAR(r.floor_peak[b][k] / ind.floor_peak[i], 1.0, 1e-10) << at << ", building " << b << ", floor " << f;
            EXPECT_NEAR(r.drift_peak[b][k] / ind.drift_peak[i], 1.0, 1e-10) << at << ", building " << b << ", storey " << f;
          }
        for (std::size_t j = 0; j < r.contacts.size(); ++j) {
          const buildings::ContactResult& c = r.contacts[j];
          EXPECT_EQ(c.impacts, ind.impacts[j]) << at << ", contact " << j;
          if (c.impacts > 0 && ind.impacts[j] > 0) {
            EXPECT_NEAR(c.first_impact, ind.first_impact[j], 1e-12 * md.t_end) << at << ", contact " << j;
            EXPECT_NEAR(c.impact_velocity_max / ind.fastest[j], 1.0, 1e-10) << at << ", contact " << j;
          }
        }
      }
  EXPECT_GE(scenes, 4);
}

// The stuck system's closed form (complex modes: two buildings of different Rayleigh damping
// joined are not classically damped) against the matrix exponential of its reduced first-order
// system, and each stuck contact's force against what the left floor's own equation needs.
TEST(BuildingsReference, StuckMotionAndForcesAreTheMatrixExponentials) {
  BuildingScene s = issue_scene();
  s.buildings.push_back(building({1e5, 1.2e5}, {1.5e8, 1.4e8}));
  const BuildingModel md = assemble(s);
  const int nf = md.n_floors, nc = static_cast<int>(md.contacts.size());
  for (const std::vector<char>& stuck : {std::vector<char>{0, 0, 1, 0, 0}, std::vector<char>{1, 1, 1, 1, 1},
                                         std::vector<char>{0, 1, 0, 0, 1}}) {
    const buildings::Reduced red = buildings::make_reduced(md, stuck);
    const buildings::Modal mo = buildings::make_modal(md, red);
    ASSERT_TRUE(mo.ok) << mo.why;
    // A state that keeps the stuck floors together: the cluster's position and velocity.
    Eigen::VectorXd qs(red.n), qv(red.n);
    for (int c = 0; c < red.n; ++c) {
      qs(c) = 0.01 * std::sin(1.7 * c + 0.3);
      qv(c) = 0.2 * std::cos(2.3 * c);
    }
    std::vector<double> u(static_cast<std::size_t>(nf)), v(static_cast<std::size_t>(nf)), g(static_cast<std::size_t>(nc));
    for (int i = 0; i < nf; ++i) {
      u[static_cast<std::size_t>(i)] = qs(red.cluster[static_cast<std::size_t>(i)]) + red.offset(i);
      v[static_cast<std::size_t>(i)] = qv(red.cluster[static_cast<std::size_t>(i)]);
    }
    for (int j = 0; j < nc; ++j) {
      const FloorContact& fc = md.contacts[static_cast<std::size_t>(j)];
      g[static_cast<std::size_t>(j)] = s.delta + u[static_cast<std::size_t>(fc.i_right)] - u[static_cast<std::size_t>(fc.i_left)];
    }
    const double t0 = 0.1;
    const LoadPiece piece = s.pulse.piece(t0);
    buildings::Motion motion;
    motion.reserve(nf, nc);
    motion.build(md, red, mo, u.data(), v.data(), g.data(), piece, t0, piece.end);
    // The reduced system, augmented with the sine's states.
    const int n = red.n, dim = 2 * n + 3;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(dim, dim);
    const Eigen::VectorXd minv = red.mass.cwiseInverse();
    a.block(0, n, n, n).setIdentity();
    a.block(n, 0, n, n) = -(minv.asDiagonal() * red.K);
    a.block(n, n, n, n) = -(minv.asDiagonal() * red.C);
    a.block(n, 2 * n, n, 1) = minv.cwiseProduct(red.f);  // the constant state 1
    const Sinusoid& w = piece.waves[0];
    a.block(n, 2 * n + 1, n, 1).setConstant(-w.s);  // -a_g per unit mass
    a.block(n, 2 * n + 2, n, 1).setConstant(-w.c);
    a(2 * n + 1, 2 * n + 2) = w.w;
    a(2 * n + 2, 2 * n + 1) = -w.w;
    Eigen::VectorXd y0(dim);
    y0 << qs, qv, 1.0, std::sin(w.w * t0), std::cos(w.w * t0);
    for (double tau : {0.0, 0.013, 0.07, 0.31}) {
      const double t = t0 + tau;
      const Eigen::VectorXd y = (a * tau).exp() * y0;
      const Eigen::VectorXd yd = a * y;
      for (int i = 0; i < nf; ++i) {
        const int c = red.cluster[static_cast<std::size_t>(i)];
        double out[2];
        motion.eval(motion.floor(i), t, out, 2);
        EXPECT_NEAR(out[0], y(c) + red.offset(i), 1e-12 * 0.05) << "floor " << i << " at " << tau;
        EXPECT_NEAR(out[1], y(n + c), 1e-12) << "floor " << i << " at " << tau;
      }
      // lambda_j = -(m u'' + C u' + K u + m a_g) of the floors of its cluster left of it.
      Eigen::VectorXd uu(nf), uv(nf), ua(nf);
      for (int i = 0; i < nf; ++i) {
        const int c = red.cluster[static_cast<std::size_t>(i)];
        uu(i) = y(c) + red.offset(i);
        uv(i) = y(n + c);
        ua(i) = yd(n + c);
      }
      const Eigen::VectorXd e = md.m.cwiseProduct(ua) + md.C * uv + md.K * uu + md.m * piece.accel(t);
      for (int j = 0; j < nc; ++j) {
        if (!stuck[static_cast<std::size_t>(j)]) continue;
        const FloorContact& fc = md.contacts[static_cast<std::size_t>(j)];
        double lambda = 0.0;
        for (int b = 0; b <= fc.left; ++b) {
          const int f = md.global(b, fc.floor);
          if (red.cluster[static_cast<std::size_t>(f)] == red.cluster[static_cast<std::size_t>(fc.i_left)]) lambda -= e(f);
        }
        double out[1];
        motion.eval(motion.contact(j), t, out, 1);
        EXPECT_NEAR(out[0], lambda, 1e-11 * 3e5 * 3.0) << "contact " << j << " at " << tau;
      }
    }
  }
}

// One storey each: the single oscillators' scenes, pair (left building = body 1, right =
// body 0) and row3 (bodies 1, 0, 2), solved by the event-driven reference of the paper's
// scenes: its Poisson law is Newton's for one contact at a time.
BuildingScene scene_of(const System& sys) {
  BuildingScene s;
  for (const Body& b : sys.bodies) s.buildings.push_back(building({b.m}, {b.k}));
  s.xi = sys.xi;
  s.delta = sys.delta;
  s.eps = sys.eps;
  s.pulse = sys.pulse;
  s.a_p = sys.a_p;
  s.w_p = sys.pulse.w;
  s.t_end = sys.t_end;
  return s;
}

struct Agreement {
  int compared = 0;
  double worst = 0.0;  // relative, of Pi1
};

// Body 0's Pi1, the impacts, the first impact and the largest approach of the two references.
void compare_with_single_oscillators(const Case& c, double tol, Agreement& agreement) {
  const System sys = make_system(c);
  const Result old = event_driven::solve(sys, {});
  ASSERT_EQ(old.status, Status::ok) << old.message;
  const buildings::BuildingsResult r = buildings::solve(scene_of(sys));
  ASSERT_EQ(r.status, Status::ok) << r.message;
  const std::string at = std::string(name(c.scene)) + " pi2 " + std::to_string(c.pi2) + " pi3 " + std::to_string(c.pi3) +
                         " pi5 " + std::to_string(c.pi5) + " pi6 " + std::to_string(c.pi6) + " eps " + std::to_string(c.eps) +
                         " " + std::string(name(c.pulse)) + " " + std::string(name(c.directivity));
  const double pi1 = sys.pi1(r.floor_peak[static_cast<std::size_t>(sys.ref)][0]);
  EXPECT_NEAR(pi1 / old.pi1, 1.0, tol) << at;
  agreement.worst = std::max(agreement.worst, std::abs(pi1 / old.pi1 - 1.0));
  long impacts = 0;
  double first = std::numeric_limits<double>::quiet_NaN(), fastest = 0.0;
  for (const buildings::ContactResult& k : r.contacts) {
    impacts += k.impacts;
    if (k.impacts > 0) {
      first = std::isnan(first) ? k.first_impact : std::min(first, k.first_impact);
      fastest = std::max(fastest, k.impact_velocity_max);
    }
  }
  EXPECT_EQ(impacts, old.impacts) << at;
  if (old.impacts > 0 && impacts > 0) {
    EXPECT_NEAR(first, old.first_impact, 1e-12 * sys.t_end) << at;
    EXPECT_NEAR(fastest / old.impact_velocity_max, 1.0, tol) << at;
  }
  ++agreement.compared;
}

TEST(BuildingsReference, OneStoreyPairIsTheSingleOscillatorsReference) {
  Agreement agreement;
  for (PulseShape shape : {PulseShape::sine, PulseShape::cosine})
    for (Directivity dir : {Directivity::normal, Directivity::reverse})
      for (double pi2 : {0.3, 1.0, 2.5})
        for (double pi3 : {0.0, 0.2, 2.0})
          for (double pi5 : {0.5, 1.33, 4.0})
            for (double pi6 : {0.5, 2.0})
              for (double eps : {0.0, 0.6, 1.0}) {
                Case c;
                c.scene = Scene::pair;
                c.pulse = shape;
                c.directivity = dir;
                c.pi2 = pi2;
                c.pi3 = pi3;
                c.pi5 = pi5;
                c.pi6 = pi6;
                c.eps = eps;
                c.a_p = 2.0;
                c.w_p = 7.0;
                compare_with_single_oscillators(c, 1e-10, agreement);
              }
  EXPECT_EQ(agreement.compared, 648);
  EXPECT_LT(agreement.worst, 1e-13);  // measured 1.2e-14
}

// Three one-storey buildings where only one contact is ever closed at a time (elastic impacts,
// a gap wide enough that no accumulation forms): there Newton's law and Poisson's coincide.
TEST(BuildingsReference, OneStoreyRowOfThreeIsTheSingleOscillatorsReference) {
  Agreement agreement;
  for (PulseShape shape : {PulseShape::sine, PulseShape::cosine})
    for (double pi2 : {0.5, 1.0, 2.0})
      for (double pi5 : {0.5, 2.0})
        for (double pi7 : {0.75, 3.0}) {
          Case c;
          c.scene = Scene::row3;
          c.pulse = shape;
          c.pi2 = pi2;
          c.pi3 = 0.5;
          c.pi5 = pi5;
          c.pi6 = 1.5;
          c.pi7 = pi7;
          c.pi8 = 0.7;
          c.eps = 1.0;
          compare_with_single_oscillators(c, 1e-10, agreement);
        }
  EXPECT_EQ(agreement.compared, 24);
  EXPECT_LT(agreement.worst, 1e-13);  // measured 1.8e-14
}

// Self-similarity (cases/README.md): masses times 7, frequencies twice, the pulse's amplitude
// three times and frequency twice, the gap with the length scale a_p / w_p^2: every floor's Pi1
// and every contact's impacts are the same.
TEST(BuildingsReference, ScenesOfEqualPiTermsHaveEqualPi1) {
  for (double gap : {0.0, 0.005, 0.03}) {
    BuildingScene s = issue_scene();
    s.delta = gap;
    s.buildings.push_back(building({1e5, 1.2e5}, {1.5e8, 1.4e8}));
    BuildingScene t = s;
    const double mass = 7.0, freq = 2.0, amp = 3.0;
    for (Building& b : t.buildings) {
      for (double& m : b.masses) m *= mass;
      for (double& k : b.stiffnesses) k *= mass * freq * freq;
    }
    t.pulse = Pulse(PulseShape::sine, s.pulse.amplitude * amp, s.pulse.w * freq);
    t.delta = s.delta * amp / (freq * freq);
    const buildings::BuildingsResult a = buildings::solve(s), b = buildings::solve(t);
    ASSERT_EQ(a.status, Status::ok) << a.message;
    ASSERT_EQ(b.status, Status::ok) << b.message;
    const double la = s.pulse.amplitude / (s.pulse.w * s.pulse.w), lb = t.pulse.amplitude / (t.pulse.w * t.pulse.w);
    for (std::size_t i = 0; i < s.buildings.size(); ++i)
      for (std::size_t f = 0; f < a.floor_peak[i].size(); ++f) {
        EXPECT_NEAR(b.floor_peak[i][f] / lb / (a.floor_peak[i][f] / la), 1.0, 1e-12) << "gap " << gap << " building " << i;
        EXPECT_NEAR(b.drift_peak[i][f] / lb / (a.drift_peak[i][f] / la), 1.0, 1e-12) << "gap " << gap << " building " << i;
      }
    for (std::size_t j = 0; j < a.contacts.size(); ++j) {
      EXPECT_EQ(a.contacts[j].impacts, b.contacts[j].impacts) << "gap " << gap << " contact " << j;
      if (a.contacts[j].impacts > 0) {
        EXPECT_NEAR(b.contacts[j].first_impact * t.pulse.w, a.contacts[j].first_impact * s.pulse.w, 1e-12);
      }
    }
  }
}

// A random scene of the whole space the scene allows.
BuildingScene random_scene(std::mt19937& rng, int max_floors) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto pick = [&](std::initializer_list<double> xs) {
    return *(xs.begin() + static_cast<std::ptrdiff_t>(rng() % xs.size()));
  };
  BuildingScene s;
  const int nb = unit(rng) < 0.3 ? 3 : 2;
  const double w_p = 2.0 + 20.0 * unit(rng), a_p = 0.5 + 5.0 * unit(rng);
  for (int b = 0; b < nb; ++b) {
    const int n = 1 + static_cast<int>(rng() % static_cast<unsigned>(max_floors));
    Building bd;
    const double w1 = w_p * std::exp(std::log(0.2) + std::log(25.0) * unit(rng));
    bd = uniform_building(n, 1e5 * (0.5 + unit(rng)), w1);
    if (unit(rng) < 0.5)  // not uniform
      for (std::size_t i = 0; i < bd.masses.size(); ++i) {
        bd.masses[i] *= 0.5 + unit(rng);
        bd.stiffnesses[i] *= 0.5 + unit(rng);
      }
    s.buildings.push_back(bd);
  }
  if (unit(rng) < 0.2) s.buildings[1] = s.buildings[0];  // identical neighbours
  s.damping = unit(rng) < 0.5 ? BuildingDamping::rayleigh : BuildingDamping::modal;
  s.xi = pick({0.0, 0.02, 0.05, 0.1, 0.3});
  s.eps = pick({0.0, 0.3, 0.6, 0.9, 1.0});
  s.delta = pick({0.0, 0.01, 0.1, 0.5, 2.0}) * a_p / (w_p * w_p);
  // The load: the paper's pulses mostly, the pulse models and a record too.
  Case c;
  c.a_p = a_p;
  c.w_p = w_p;
  c.directivity = unit(rng) < 0.5 ? Directivity::normal : Directivity::reverse;
  const double shape = unit(rng);
  c.pulse = shape < 0.35 ? PulseShape::sine : shape < 0.7 ? PulseShape::cosine : shape < 0.8 ? PulseShape::makris_c
          : shape < 0.9 ? PulseShape::mp : PulseShape::record;
  c.cycles = 2;
  c.mp_gamma = 2.5;
  c.mp_nu = 45.0;
  if (c.pulse == PulseShape::record) {
    auto rec = std::make_shared<Record>();
    rec->source = "synthetic";
    const double dt = 0.3 / w_p;  // some twenty samples a pulse period
    for (int i = 0; i <= 60; ++i) {
      rec->t.push_back(dt * i);
      rec->a.push_back(i == 0 ? 0.0 : a_p * std::sin(0.5 * i) * std::exp(-0.03 * i) + 0.2 * a_p * (unit(rng) - 0.5));
      rec->peak = std::max(rec->peak, std::abs(rec->a.back()));
    }
    c.samples = rec;
  }
  s.pulse = make_pulse(c);
  s.a_p = a_p;
  s.w_p = w_p;
  return s;
}

TEST(BuildingsReference, RandomScenesSolveWithTheirEnergyBalance) {
  std::mt19937 rng(49);
  int n_ok = 0;
  double worst = 0.0;
  for (int k = 0; k < 200; ++k) {
    const BuildingScene s = random_scene(rng, 6);
    const buildings::BuildingsResult r = buildings::solve(s);
    EXPECT_EQ(r.status, Status::ok) << "scene " << k << ": " << r.message;
    if (r.status == Status::ok) ++n_ok;
    worst = std::max(worst, r.energy_error);
  }
  EXPECT_EQ(n_ok, 200);
  EXPECT_LT(worst, 1e-11);  // measured 8.9e-14 (and 1.1e-12 on one of 300, a cosine pulse with 493 events)
}

// The issue's 3 + 3 storey pair at a 5 mm gap: it pounds at every floor, floors stick, and the
// energy the ground put in is what the buildings hold plus what damping and impacts took.
TEST(BuildingsReference, IssuePairPoundsWithItsEnergyBalanced) {
  BuildingScene s = issue_scene();
  s.delta = 0.005;
  const BuildingModel md = assemble(s);
  const buildings::BuildingsResult r = buildings::solve(md);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  ASSERT_EQ(r.contacts.size(), 3u);
  long phases = 0;
  for (const buildings::ContactResult& c : r.contacts) {
    EXPECT_GT(c.impacts, 0) << "floor " << c.floor;
    EXPECT_GT(c.impact_velocity_max, 0.0);
    EXPECT_GT(c.first_impact, 0.0);
    EXPECT_LT(c.first_impact, md.t_end);
    phases += c.contact_phases;
  }
  EXPECT_GT(phases, 0);
  // Pounding shortens the flexible right building's top storeys' travel, as its no-contact run shows.
  BuildingScene apart = s;
  apart.no_contact = true;
  const buildings::BuildingsResult free = buildings::solve(apart);
  ASSERT_EQ(free.status, Status::ok) << free.message;
  EXPECT_LT(r.floor_peak[1][2], free.floor_peak[1][2]);
  const buildings::Energies& e = r.energies;
  EXPECT_GT(e.input, 0.0);
  EXPECT_GT(e.damped, 0.0);
  EXPECT_GT(e.impacts, 0.0);
  EXPECT_GE(e.kinetic, 0.0);
  EXPECT_GE(e.elastic, 0.0);
  EXPECT_NEAR(e.input, e.kinetic + e.elastic + e.damped + e.impacts, 1e-12 * e.input);
  EXPECT_LT(r.energy_error, 1e-12);
  // Without damping, elastic impacts lose nothing (no floor sticks here: sticking would).
  BuildingScene elastic = s;
  elastic.xi = 0.0;
  elastic.eps = 1.0;
  elastic.delta = 0.03;
  const buildings::BuildingsResult kept = buildings::solve(elastic);
  ASSERT_EQ(kept.status, Status::ok) << kept.message;
  EXPECT_EQ(kept.energies.damped, 0.0);
  for (const buildings::ContactResult& c : kept.contacts) EXPECT_EQ(c.contact_phases, 0);
  EXPECT_NEAR(kept.energies.impacts, 0.0, 1e-12 * kept.energies.input);
}

TEST(BuildingsReference, LimitsEndARunWithTheirStatus) {
  BuildingScene s = issue_scene();
  s.delta = 0.005;
  Settings cap;
  cap.step_cap = 10;
  const buildings::BuildingsResult capped = buildings::solve(s, cap);
  EXPECT_EQ(capped.status, Status::step_cap);
  EXPECT_NE(capped.message.find("10 events"), std::string::npos) << capped.message;
  BuildingScene bad = s;
  bad.xi = 1.0;
  const buildings::BuildingsResult refused = buildings::solve(bad);
  EXPECT_EQ(refused.status, Status::failed);
  EXPECT_EQ(refused.message, validate(bad));
}

}  // namespace buildings_reference_tests
}  // namespace pb
