// The buildings scene's model (cases/buildings.hpp) against closed forms: a uniform
// building's frequencies, the damping rules' ratios, the contacts, the duration, validation.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include "cases/buildings.hpp"
#include "kit/testing_buildings.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace buildings_model_tests {

using test::building;
using test::issue_scene;
using std::numbers::pi;

// ---- The model -------------------------------------------------------------------------

TEST(BuildingsModel, UniformBuildingFrequenciesAreTheClosedForm) {
  for (int n : {1, 2, 3, 7, 20, 60}) {
    const double m = 2.5e5, k = 3.1e8;
    Building b;
    b.masses.assign(static_cast<std::size_t>(n), m);
    b.stiffnesses.assign(static_cast<std::size_t>(n), k);
    const BuildingModes modes = building_modes(b);
    for (int r = 1; r <= n; ++r) {
      const double exact = 2.0 * std::sqrt(k / m) * std::sin((2.0 * r - 1.0) * pi / (2.0 * (2.0 * n + 1.0)));
      EXPECT_NEAR(modes.w(r - 1) / exact, 1.0, 1e-13) << "n = " << n << ", mode " << r;
    }
  }
}

TEST(BuildingsModel, ModesAreMassNormalisedAndSolveTheEigenproblem) {
  const BuildingModel md = assemble(issue_scene());
  for (std::size_t b = 0; b < 2; ++b) {
    const auto block = Eigen::seqN(md.first[b], 3);
    const Eigen::MatrixXd m = md.m(block).asDiagonal();
    const Eigen::MatrixXd k = md.K(block, block);
    const BuildingModes& modes = md.modes[b];
    EXPECT_LT((modes.phi.transpose() * m * modes.phi - Eigen::MatrixXd::Identity(3, 3)).norm(), 1e-14);
    const Eigen::MatrixXd residual = k * modes.phi - m * modes.phi * modes.w.cwiseAbs2().asDiagonal();
    EXPECT_LT(residual.norm() / k.norm(), 1e-14);
  }
}

TEST(BuildingsModel, RayleighDampingHasRatioXiInModesOneAndTwo) {
  BuildingScene s = issue_scene();
  s.buildings[0] = uniform_building(8, 2e5, 6.0);
  s.xi = 0.07;
  const BuildingModel md = assemble(s);
  for (std::size_t b = 0; b < 2; ++b) {
    const int n = s.buildings[b].floors();
    const auto block = Eigen::seqN(md.first[b], n);
    const BuildingModes& modes = md.modes[b];
    const Eigen::MatrixXd modal = modes.phi.transpose() * md.C(block, block) * modes.phi;
    for (int r = 0; r < 2; ++r) EXPECT_NEAR(modal(r, r) / (2.0 * modes.w(r)), 0.07, 1e-15) << "mode " << r + 1;
    // Classical: no coupling between modes, and each mode's ratio as the model states it.
    for (int r = 0; r < n; ++r) {
      EXPECT_NEAR(modal(r, r) / (2.0 * modes.w(r)), modes.xi(r), 1e-14);
      for (int c = 0; c < n; ++c) {
        if (c != r) {
          EXPECT_NEAR(modal(r, c), 0.0, 1e-12 * modal(r, r));
        }
      }
    }
    EXPECT_GT(modes.xi(n - 1), 0.07);  // higher modes are damped more
  }
}

TEST(BuildingsModel, OneStoreyRayleighDampingIsTwoXiWM) {
  BuildingScene s = issue_scene();
  s.buildings = {building({2e5}, {3e8}), building({1e5}, {5e7})};
  const BuildingModel md = assemble(s);
  for (int i = 0; i < 2; ++i) {
    const double w = std::sqrt(md.K(i, i) / md.m(i));
    EXPECT_NEAR(md.C(i, i), 2.0 * 0.05 * w * md.m(i), 1e-15 * md.C(i, i));
  }
}

TEST(BuildingsModel, ModalDampingHasRatioXiInEveryMode) {
  BuildingScene s = issue_scene();
  s.damping = BuildingDamping::modal;
  s.xi = 0.2;
  const BuildingModel md = assemble(s);
  for (std::size_t b = 0; b < 2; ++b) {
    const auto block = Eigen::seqN(md.first[b], 3);
    const BuildingModes& modes = md.modes[b];
    const Eigen::MatrixXd modal = modes.phi.transpose() * md.C(block, block) * modes.phi;
    const Eigen::MatrixXd expected = (2.0 * 0.2 * modes.w).asDiagonal();
    EXPECT_LT((modal - expected).norm(), 1e-13 * expected.norm());
  }
}

TEST(BuildingsModel, ContactsAreEveryFloorBothNeighboursHaveOrTheNamedOnes) {
  BuildingScene s = issue_scene();
  s.buildings.push_back(building({1e5, 1e5}, {1e8, 1e8}));
  BuildingModel md = assemble(s);
  ASSERT_EQ(md.contacts.size(), 5u);  // 3 between buildings 0 and 1, 2 between 1 and 2
  EXPECT_EQ(md.contacts[3].left, 1);
  EXPECT_EQ(md.contacts[3].floor, 1);
  EXPECT_EQ(md.contacts[3].i_left, md.global(1, 1));
  EXPECT_EQ(md.contacts[3].i_right, md.global(2, 1));
  s.contact_floors = {2};
  md = assemble(s);
  ASSERT_EQ(md.contacts.size(), 2u);
  EXPECT_EQ(md.contacts[0].floor, 2);
  EXPECT_EQ(md.contacts[1].floor, 2);
}

TEST(BuildingsModel, DefaultDurationIsThePulsePlusThreeSlowestPeriods) {
  const BuildingScene s = issue_scene();
  const BuildingModel md = assemble(s);
  const double t1 = 2.0 * pi / std::min(md.modes[0].w(0), md.modes[1].w(0));
  EXPECT_DOUBLE_EQ(md.t_end, 2.0 * pi / 12.566 + 3.0 * t1);
  BuildingScene given = s;
  given.t_end = 2.5;
  EXPECT_EQ(assemble(given).t_end, 2.5);
}

TEST(BuildingsModel, InvalidScenesSayWhyInOneLine) {
  const auto why = [](auto change) {
    BuildingScene s = issue_scene();
    change(s);
    return validate(s);
  };
  EXPECT_EQ(validate(issue_scene()), "");
  EXPECT_NE(why([](BuildingScene& s) { s.buildings.resize(1); }).find("two or three"), std::string::npos);
  EXPECT_NE(why([](BuildingScene& s) { s.buildings[1].masses[2] = 0.0; }).find("mass of floor 3"), std::string::npos);
  EXPECT_NE(why([](BuildingScene& s) { s.buildings[0].stiffnesses[0] = -1.0; }).find("stiffness of storey 1"),
            std::string::npos);
  EXPECT_NE(why([](BuildingScene& s) { s.buildings[0].stiffnesses.pop_back(); }).find("one per storey"),
            std::string::npos);
  EXPECT_NE(why([](BuildingScene& s) { s.xi = 1.0; }).find("xi"), std::string::npos);
  EXPECT_NE(why([](BuildingScene& s) { s.delta = -0.01; }).find("gap"), std::string::npos);
  EXPECT_NE(why([](BuildingScene& s) { s.eps = 1.5; }).find("eps"), std::string::npos);
  EXPECT_NE(why([](BuildingScene& s) { s.contact_floors = {4}; }).find("floor 4"), std::string::npos);
  EXPECT_NE(why([](BuildingScene& s) { s.contact_floors = {2, 2}; }).find("twice"), std::string::npos);
  for (const std::string& w : {why([](BuildingScene& s) { s.xi = 2.0; }), why([](BuildingScene& s) { s.eps = -1; })})
    EXPECT_EQ(w.find('\n'), std::string::npos);
}

}  // namespace buildings_model_tests
}  // namespace pb
