// MuJoCo on the buildings scene (solvers/mujoco/buildings.hpp): its faithful variants against
// the exact reference (solvers/buildings_reference/) as the step shrinks, on points of the case
// sets; its model without contact; its default variant runs; the statuses of a run that cannot
// finish.
//
// Errors are relative, the largest over every floor's peak |u| of every building. MuJoCo's
// contacts are soft, calibrated to eps with a time constant of a few steps, and an impact's
// restitution scatters with where in its step the contact starts, at every h (README.md, "The
// finding"): the faithful variants creep towards the reference without a clean order, so the
// tests assert a fall from the coarse step to the fine one by a margin, and state the measured
// errors beside them.

#ifdef POUNDBENCH_HAVE_MUJOCO

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include "cases/buildings.hpp"
#include "cases/buildings_set.hpp"
#include "kit/fixed_step.hpp"
#include "kit/testing.hpp"
#include "kit/testing_buildings.hpp"
#include "solvers/buildings_reference/reference.hpp"
#include "solvers/mujoco/buildings.hpp"
#include "solvers/registry.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace buildings_mujoco_tests {

using buildings::BuildingsResult;
using test::floor_error;
using test::floors_hit;

BuildingsResult run(const BuildingModel& md, const std::string& variant, int steps) {
  Settings set;
  set.variant = variant;
  set.steps = steps;
  return mujoco::solve_buildings(md, set);
}

// The errors of a variant at the steps ns.
std::vector<double> errors(const BuildingModel& md, const BuildingsResult& ref, const std::string& variant,
                           std::initializer_list<int> ns) {
  std::vector<double> e;
  for (int n : ns) {
    const BuildingsResult r = run(md, variant, n);
    EXPECT_EQ(r.status, Status::ok) << variant << " N " << n << ": " << r.message;
    e.push_back(floor_error(r, ref));
  }
  return e;
}

// The model without contact (the buildings 1 m apart): the slide joints, the storeys' tendons
// and the damping (Rayleigh by joint and tendon dampers, modal applied) are the reference's
// motion, at first order for Euler and fourth for RK4. Measured on the issue's pair, Rayleigh
// and modal, the largest floor-peak error at N = 64, 256, 1024: Euler 9.8e-4, 2.4e-4, 6.0e-5
// (modal; Rayleigh 4.7e-4 to 2.9e-5), RK4 1.4e-5, 1.1e-6, 8.2e-8.
TEST(BuildingsMujoco, ModelWithoutContactIsTheReferences) {
  for (BuildingDamping damping : {BuildingDamping::rayleigh, BuildingDamping::modal}) {
    BuildingScene s = test::issue_scene();
    s.delta = 1.0;
    s.damping = damping;
    const BuildingModel md = assemble(s);
    const BuildingsResult ref = buildings::solve(md);
    ASSERT_EQ(ref.status, Status::ok) << ref.message;
    const std::vector<double> euler = errors(md, ref, "euler-faithful", {64, 256, 1024});
    EXPECT_LT(euler[2], euler[0] / 10.0) << test::sci(euler[0]) << " " << test::sci(euler[2]);
    EXPECT_LT(euler[2], 2e-4);
    const std::vector<double> rk4 = errors(md, ref, "rk4-faithful", {64, 256, 1024});
    EXPECT_LT(rk4[2], rk4[0] / 100.0) << test::sci(rk4[0]) << " " << test::sci(rk4[2]);
    EXPECT_LT(rk4[2], 1e-6);
  }
}

struct Point {
  const char* set;
  std::size_t p;
};

// buildings-stress.toml point 0 (3 storeys against 6 touching at rest, eps 0: floors 2 and 3
// close within 0.5 ms of each other and stick, floor 1 sticks too) and point 4 (three buildings
// in a row, 10 mm gaps: the middle one takes impacts from both sides at 4 floors). Measured, the
// largest floor-peak error at N = 64, 512, 4096 (RK4: 64, 256, 1024):
//   euler-faithful     1.1e-2, 1.2e-3, 1.7e-4;  2.5e-2, 1.2e-2, 3.6e-3
//   implicit-faithful  5.4e-3, 3.9e-4, 7.2e-5;  2.4e-2, 8.0e-3, 1.3e-3
//   rk4-faithful       1.6e-2, 4.4e-3, 1.2e-3;  2.7e-2, 6.0e-3, 2.2e-3
// On buildings.toml point 0 (a 20 mm gap, eps 0.6: 37 impacts at floor 3 accumulating into a
// contact) the restitution's scatter stalls them: Euler 2.0e-2, 1.5e-2, 1.6e-2, 1.1e-2 at
// N = 64, 256, 1024, 4096 (README, "Buildings").
TEST(BuildingsMujoco, FaithfulVariantsApproachTheReference) {
  for (const Point pt : {Point{"buildings-stress.toml", 0}, Point{"buildings-stress.toml", 4}}) {
    const BuildingModel md = test::shipped_point(pt.set, pt.p);
    const BuildingsResult ref = buildings::solve(md);
    ASSERT_EQ(ref.status, Status::ok) << ref.message;
    EXPECT_GE(floors_hit(ref), 2) << pt.set << " point " << pt.p << ": impacts at several floors";
    for (const char* v : {"euler-faithful", "implicit-faithful", "rk4-faithful"}) {
      const bool rk4 = std::string(v) == "rk4-faithful";  // four evaluations a step: shorter runs
      const std::vector<double> e = rk4 ? errors(md, ref, v, {64, 256, 1024}) : errors(md, ref, v, {64, 512, 4096});
      const std::string what = std::string(pt.set) + " point " + std::to_string(pt.p) + " " + v + ": " +
                               test::sci(e[0]) + " " + test::sci(e[1]) + " " + test::sci(e[2]);
      EXPECT_LT(e[2], e[0] / 5.0) << what;
      EXPECT_LT(e[2], 5e-3) << what;
      RecordProperty(std::string(v) + "_" + std::to_string(pt.p), what);
    }
  }
  const BuildingModel md = test::shipped_point("buildings.toml", 0);
  const BuildingsResult r = run(md, "euler-faithful", 4096);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_LT(floor_error(r, buildings::solve(md)), 2e-2);
}

// The default variant (MuJoCo's own contact, solref 0.02 1, eps not used) runs through and gives
// finite peaks; it does not converge to the reference, whose restitution it does not model:
// measured on buildings.toml point 0, the largest floor-peak error 4.8e-2, 4.9e-2, 5.0e-2,
// 5.0e-2 at N = 64, 256, 1024, 4096.
TEST(BuildingsMujoco, DefaultVariantRunsAndGivesFinitePeaks) {
  const BuildingModel md = test::shipped_point("buildings.toml", 0);
  const BuildingsResult ref = buildings::solve(md);
  const BuildingsResult r = run(md, "default", 256);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_GE(floors_hit(r), 2);
  for (const auto& b : r.floor_peak)
    for (double x : b) EXPECT_TRUE(std::isfinite(x) && x > 0.0);
  EXPECT_LT(floor_error(r, ref), 0.1);
}

// A step too long, one past the pulse, the time limit, the stop flag, an unknown variant
// (kit/testing_buildings.hpp).
TEST(BuildingsMujoco, StatusesOfARunThatCannotFinish) {
  test::expect_buildings_statuses(&mujoco::solve_buildings, "euler-faithful");
}

// The registry's mujoco row solves the scene and lists what its solve reads.
TEST(BuildingsMujoco, RegistryRowSolvesTheScene) {
  const SolverInfo* info = find_solver("mujoco");
  ASSERT_NE(info, nullptr);
  ASSERT_NE(info->solve_buildings, nullptr);
  EXPECT_EQ(info->buildings_settings.size(), std::size(mujoco::kBuildingsSettings));
  const BuildingsResult r = info->solve_buildings(assemble(test::issue_scene()), Settings{});
  EXPECT_EQ(r.status, Status::ok) << r.message;
  EXPECT_EQ(r.events, step_count(r.t_end, r.step));
}

}  // namespace buildings_mujoco_tests
}  // namespace pb

#endif  // POUNDBENCH_HAVE_MUJOCO
