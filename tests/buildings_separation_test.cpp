// The gap that avoids pounding between buildings, per floor level (cases/README.md,
// "Separation"): the exact reference's free watch (buildings::free_motion) against an
// independent integration, the gap at which impacts stop, and the rules per floor level.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Dense>

#include "cases/buildings_set.hpp"
#include "kit/separation.hpp"
#include "solvers/buildings_reference/reference.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace buildings_separation_tests {

const std::string kBuildingsSet = std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/buildings.toml";

BuildingCase shipped_point(std::size_t i) {
  const std::optional<BuildingsSet> set = load_buildings_set(kBuildingsSet);
  if (!set || i >= set->points.size()) throw std::runtime_error("no point " + std::to_string(i));
  return set->points[i];
}

// The first point of the 3-and-6-storey family under the cosine pulse (a load that jumps to 0 at
// T_p), its damping made modal.
BuildingCase modal_point() {
  const std::optional<BuildingsSet> set = load_buildings_set(kBuildingsSet);
  for (const BuildingCase& c : set->points)
    if (c.family == "3-and-6-storeys" && c.pulse == PulseShape::cosine) {
      BuildingCase m = c;
      m.scene.damping = BuildingDamping::modal;
      return m;
    }
  throw std::runtime_error("no cosine point");
}

struct Extremes {
  std::vector<double> closing, opening;  // per contact: max(u_left - u_right), max(u_right - u_left)
};

// An independent integration of M u'' + C u' + K u = -M 1 a_g with every contact removed: RK4 of
// `per_period` steps per shortest period, on the pulse and after it apart (the load may jump at
// T_p), each floor pair's relative displacement at every step end and, in each step where its
// velocity changes sign, at 64 points of the step's cubic Hermite interpolant (error O(h^4)).
Extremes rk4_extremes(const BuildingScene& scene, int per_period) {
  BuildingScene apart = scene;
  apart.delta = 0.0;
  const BuildingModel md = assemble(apart);
  const int n = md.n_floors;
  const Eigen::VectorXd inv_m = md.m.cwiseInverse();
  const auto accel = [&](const Eigen::VectorXd& u, const Eigen::VectorXd& v, double ag) {
    Eigen::VectorXd a = -inv_m.cwiseProduct(md.C * v + md.K * u);
    a.array() -= ag;
    return a;
  };
  Extremes out;
  out.closing.assign(md.contacts.size(), 0.0);
  out.opening.assign(md.contacts.size(), 0.0);
  const auto watch = [&](const Eigen::VectorXd& u0, const Eigen::VectorXd& v0, const Eigen::VectorXd& u1,
                         const Eigen::VectorXd& v1, double h) {
    for (std::size_t j = 0; j < md.contacts.size(); ++j) {
      const FloorContact& c = md.contacts[j];
      const double d0 = u0(c.i_left) - u0(c.i_right), d1 = u1(c.i_left) - u1(c.i_right);
      const double s0 = v0(c.i_left) - v0(c.i_right), s1 = v1(c.i_left) - v1(c.i_right);
      const auto take = [&](double d) {
        out.closing[j] = std::max(out.closing[j], d);
        out.opening[j] = std::max(out.opening[j], -d);
      };
      take(d1);
      if ((s0 > 0.0) == (s1 > 0.0)) continue;
      for (int k = 1; k < 64; ++k) {
        const double s = k / 64.0, s2 = s * s, s3 = s2 * s;
        take((2 * s3 - 3 * s2 + 1) * d0 + (s3 - 2 * s2 + s) * h * s0 + (-2 * s3 + 3 * s2) * d1 + (s3 - s2) * h * s1);
      }
    }
  };
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n), v = Eigen::VectorXd::Zero(n);
  const double t_p = scene.pulse.duration();
  const double h_max = md.t_min / per_period;
  for (const auto& [start, end, loaded] : {std::tuple{0.0, t_p, true}, std::tuple{t_p, md.t_end, false}}) {
    const long steps = static_cast<long>(std::ceil((end - start) / h_max));
    const double h = (end - start) / static_cast<double>(steps);
    const auto ag = [&](double t) { return loaded ? scene.pulse.accel(std::min(t, t_p)) : 0.0; };
    for (long i = 0; i < steps; ++i) {
      const double t = start + static_cast<double>(i) * h;
      const Eigen::VectorXd k1u = v, k1v = accel(u, v, ag(t));
      const Eigen::VectorXd k2u = v + 0.5 * h * k1v, k2v = accel(u + 0.5 * h * k1u, k2u, ag(t + 0.5 * h));
      const Eigen::VectorXd k3u = v + 0.5 * h * k2v, k3v = accel(u + 0.5 * h * k2u, k3u, ag(t + 0.5 * h));
      const Eigen::VectorXd k4u = v + h * k3v, k4v = accel(u + h * k3u, k4u, ag(t + h));
      const Eigen::VectorXd u1 = u + h / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
      const Eigen::VectorXd v1 = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
      watch(u, v, u1, v1, h);
      u = u1;
      v = v1;
    }
  }
  return out;
}

void expect_watch_matches_rk4(const BuildingCase& c) {
  const buildings::BuildingsResult free = buildings::free_motion(c.scene);
  ASSERT_EQ(free.status, Status::ok) << free.message;
  const Extremes rk4 = rk4_extremes(c.scene, 1000);
  ASSERT_EQ(free.contacts.size(), rk4.closing.size());
  ASSERT_EQ(free.contacts.size(), 3u);  // floors 1..3 of the 3- and 6-storey pair
  for (std::size_t j = 0; j < free.contacts.size(); ++j) {
    const buildings::ContactResult& k = free.contacts[j];
    EXPECT_EQ(k.impacts, 0);
    EXPECT_GT(k.closing, 0.0);
    EXPECT_GT(k.opening, 0.0);
    EXPECT_NEAR(k.closing, rk4.closing[j], 1e-7 * rk4.closing[j]) << "floor " << k.floor;
    EXPECT_NEAR(k.opening, rk4.opening[j], 1e-7 * rk4.opening[j]) << "floor " << k.floor;
  }
}

TEST(BuildingsSeparation, FreeWatchIsTheRelativeDisplacementsExtremesOfAnIndependentIntegration) {
  expect_watch_matches_rk4(shipped_point(0));
}

TEST(BuildingsSeparation, FreeWatchMatchesAnIndependentIntegrationWithModalDampingAndAJumpingLoad) {
  expect_watch_matches_rk4(modal_point());
}

// The watch adds quantities but changes no floor's motion: its peaks are the no-contact solve's
// to the last bit (the rows' no-contact peaks and the baselines rest on this).
TEST(BuildingsSeparation, FreeMotionsPeaksAreTheNoContactSolvesBitForBit) {
  const BuildingCase c = shipped_point(0);
  BuildingScene apart = c.scene;
  apart.no_contact = true;
  const buildings::BuildingsResult free = buildings::free_motion(c.scene), plain = buildings::solve(apart);
  ASSERT_EQ(plain.status, Status::ok);
  EXPECT_EQ(free.floor_peak, plain.floor_peak);
  EXPECT_EQ(free.drift_peak, plain.drift_peak);
  EXPECT_EQ(free.events, plain.events);
  EXPECT_TRUE(plain.contacts.empty());
}

// Linear buildings: under the load reversed the motion is -u, so its closing is the opening of
// the load as given.
TEST(BuildingsSeparation, TheReversedLoadsGapIsTheOpeningSide) {
  const BuildingCase c = shipped_point(0);
  BuildingScene reversed = c.scene;
  reversed.pulse.amplitude = -reversed.pulse.amplitude;
  const buildings::BuildingsResult given = buildings::free_motion(c.scene), back = buildings::free_motion(reversed);
  ASSERT_EQ(back.status, Status::ok);
  for (std::size_t j = 0; j < given.contacts.size(); ++j) {
    EXPECT_NEAR(back.contacts[j].closing, given.contacts[j].opening, 1e-12 * given.contacts[j].opening);
    EXPECT_NEAR(back.contacts[j].opening, given.contacts[j].closing, 1e-12 * given.contacts[j].closing);
  }
}

// The required gap is where impacts stop: the reference with contacts at a gap a hair above it
// has none, a hair below it has some.
TEST(BuildingsSeparation, ImpactsStopAtTheRequiredGap) {
  const BuildingCase c = shipped_point(0);
  const buildings::BuildingsResult free = buildings::free_motion(c.scene);
  ASSERT_EQ(free.status, Status::ok);
  double required = 0.0;
  for (const buildings::ContactResult& k : free.contacts) required = std::max(required, k.closing);
  ASSERT_GT(required, c.scene.delta);  // the shipped point pounds at its own gap
  const auto impacts = [&](double gap) {
    BuildingScene s = c.scene;
    s.delta = gap;
    const buildings::BuildingsResult r = buildings::solve(s);
    EXPECT_EQ(r.status, Status::ok) << r.message;
    long n = 0;
    for (const buildings::ContactResult& k : r.contacts) n += k.impacts + k.contact_phases;
    return n;
  };
  EXPECT_EQ(impacts(required * (1.0 + 1e-9)), 0);
  EXPECT_GT(impacts(required * (1.0 - 1e-6)), 0);
}

// The rules per floor level from the two floors' own no-contact peaks, DDC with the CQC
// coefficient of the buildings' first modes.
TEST(BuildingsSeparation, RulesPerFloorLevelFollowTheirFormulas) {
  for (const BuildingCase& c : {shipped_point(0), modal_point()}) {
    const BuildingModel md = assemble(c.scene);
    const buildings::BuildingsResult free = buildings::free_motion(c.scene);
    const std::vector<FloorSeparation> seps = floor_separations(md, free);
    ASSERT_EQ(seps.size(), 3u);
    const double w_a = building_modes(c.scene.buildings[0]).w(0), w_b = building_modes(c.scene.buildings[1]).w(0);
    const double xi = c.scene.xi, r = w_b / w_a;
    const double rho = 8.0 * xi * xi * (1.0 + r) * std::pow(r, 1.5) /
                       ((1.0 - r * r) * (1.0 - r * r) + 4.0 * xi * xi * r * (1.0 + r * r) + 4.0 * 2.0 * xi * xi * r * r);
    ASSERT_GT(rho, 0.0);
    for (std::size_t j = 0; j < seps.size(); ++j) {
      const FloorSeparation& s = seps[j];
      EXPECT_EQ(s.floor, static_cast<int>(j) + 1);
      EXPECT_EQ(s.required, free.contacts[j].closing);
      EXPECT_EQ(s.reversed, free.contacts[j].opening);
      const double a = free.floor_peak[0][j], b = free.floor_peak[1][j];
      EXPECT_EQ(s.peak_left, a);
      EXPECT_EQ(s.peak_right, b);
      EXPECT_NEAR(s.period_ratio, w_a / w_b, 1e-14);
      EXPECT_NEAR(s.rho, rho, 1e-12);
      EXPECT_NEAR(s.rules.abs, a + b, 1e-15 * (a + b));
      EXPECT_NEAR(s.rules.srss, std::sqrt(a * a + b * b), 1e-15 * (a + b));
      EXPECT_NEAR(s.rules.ddc, std::sqrt(a * a + b * b - 2.0 * rho * a * b), 1e-12 * (a + b));
      // The exact gap is within what ABS allows: the floors cannot approach by more than both peaks.
      EXPECT_LE(s.required, s.rules.abs);
      EXPECT_LE(s.reversed, s.rules.abs);
    }
  }
}

}  // namespace buildings_separation_tests
}  // namespace pb
