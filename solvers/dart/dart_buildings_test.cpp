// DART on the buildings scene (solvers/dart/buildings.hpp) against the exact reference
// (solvers/buildings_reference/) as the step shrinks: the faithful variants are ODE's
// faithful scheme, first order, so their peaks converge to the reference's; the default
// variant runs and gives finite peaks; the limits end a run with their statuses. Built only
// when CMake finds DART (tests/CMakeLists.txt).
//
// Errors are relative, the largest over every floor's peak |u| and every storey's peak drift
// of every building, at N = 64, 256, 1024 steps per shortest period.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <vector>

#include "cases/buildings.hpp"
#include "kit/fixed_step.hpp"
#include "kit/testing.hpp"
#include "kit/testing_buildings.hpp"
#include "solvers/buildings_reference/reference.hpp"
#include "solvers/dart/buildings.hpp"
#include "solvers/registry.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace buildings_dart_tests {

using buildings::BuildingsResult;
using test::floors_hit;
using test::issue_scene;

BuildingsResult run_dart(const BuildingModel& md, const char* variant, int steps) {
  Settings set;
  set.variant = variant;
  set.steps = steps;
  return dart::solve_buildings(md, set);
}

long impacts(const BuildingsResult& r) {
  long n = 0;
  for (const auto& c : r.contacts) n += c.impacts;
  return n;
}

// The errors of a faithful variant at N = 64, 256, 1024, each run ending ok.
std::vector<double> errors(const BuildingModel& md, const char* variant, const std::string& what) {
  const BuildingsResult ref = buildings::solve(md);
  EXPECT_EQ(ref.status, Status::ok) << ref.message;
  std::vector<double> e;
  for (int n : {64, 256, 1024}) {
    const BuildingsResult r = run_dart(md, variant, n);
    EXPECT_EQ(r.status, Status::ok) << what << " " << variant << " N=" << n << ": " << r.message;
    e.push_back(test::floor_error(r, ref, true));
  }
  ::testing::Test::RecordProperty(what + "_" + variant,
                                  test::sci(e[0]) + " " + test::sci(e[1]) + " " + test::sci(e[2]));
  return e;
}

// The issue's 3 + 3 pair with its 30 mm gap: impacts at floors 2 and 3, alone each.
// Measured, both variants to the digits shown: 5.1e-2, 1.8e-3, 1.0e-3 at N = 64, 256, 1024.
TEST(BuildingsDart, FaithfulConvergesToTheReferenceOnTheIssuePair) {
  const BuildingModel md = assemble(issue_scene());
  ASSERT_GT(impacts(run_dart(md, "dantzig-faithful", 256)), 0) << "the pair must pound";
  for (const char* v : {"dantzig-faithful", "pgs-faithful"}) {
    const std::vector<double> e = errors(md, v, "issue_pair");
    EXPECT_LT(e[2], e[0] / 8.0) << v;
    EXPECT_LT(e[2], 3e-3) << v;
  }
}

// Impacts at several floors at once: the buildings-stress set's three in a row, modally
// damped (a full C per building, applied whole; the middle building takes impacts from both
// sides), and the issue's pair touching at rest but for 1e-9 a_p / w_p^2 (every floor closes
// within 2 ms of the others). Measured, both variants to the digits shown: three in a row
// 1.7e-2, 2.3e-3, 5.8e-4 at N = 64, 256, 1024; touching 1.2e-3, 2.9e-4, 7.2e-5.
TEST(BuildingsDart, FaithfulConvergesWhereSeveralFloorsImpact) {
  BuildingScene three = issue_scene();
  three.buildings = {test::building({3e5, 3e5, 3e5}, {6.6e8, 6.6e8, 6.6e8}),
                     test::building({3e5, 3e5, 3e5, 3e5, 3e5, 3e5}, {5.7e8, 5.7e8, 5.7e8, 5.7e8, 5.7e8, 5.7e8}),
                     test::building({3e5, 3e5, 3e5, 3e5}, {9e8, 9e8, 9e8, 9e8})};
  three.damping = BuildingDamping::modal;
  three.delta = 0.01;
  three.eps = 0.5;
  three.pulse = Pulse(PulseShape::sine, 3.0, 2.0 * 3.141592653589793 / 0.5);
  BuildingScene touching = issue_scene();
  touching.delta = 1e-9 * touching.pulse.amplitude / (touching.pulse.w * touching.pulse.w);
  int scene = 0;
  for (const BuildingScene& s : {three, touching}) {
    const BuildingModel md = assemble(s);
    EXPECT_GE(floors_hit(run_dart(md, "dantzig-faithful", 256)), 2) << "scene " << scene << ": several floors";
    for (const char* v : {"dantzig-faithful", "pgs-faithful"}) {
      const std::vector<double> e = errors(md, v, "scene" + std::to_string(scene));
      EXPECT_LT(e[2], e[0] / 4.0) << "scene " << scene << " " << v;
      EXPECT_LT(e[2], 2e-3) << "scene " << scene << " " << v;
    }
    ++scene;
  }
}

// The default variant (boxes via FCL, joint springs, DART's defaults) runs both scenes to the
// end with finite, nonzero peaks and impacts. Its error at N = 64 (measured 0.20 and 0.21) is
// its contact's: eps on each shape restitutes eps^2, nothing below DART's bounce threshold.
TEST(BuildingsDart, DefaultRunsAndGivesFinitePeaks) {
  BuildingScene modal = issue_scene();
  modal.damping = BuildingDamping::modal;
  for (const BuildingScene& s : {issue_scene(), modal}) {
    const BuildingModel md = assemble(s);
    const BuildingsResult r = run_dart(md, "default", 64);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_GT(impacts(r), 0);
    for (const auto& building : r.floor_peak)
      for (double x : building) {
        EXPECT_TRUE(std::isfinite(x));
        EXPECT_GT(x, 0.0);
      }
    RecordProperty(s.damping == BuildingDamping::modal ? "default_modal_error" : "default_rayleigh_error",
                   test::sci(test::floor_error(r, buildings::solve(md), true)));
  }
}

// Without contact (a gap of 10 m) the default model is the buildings' own: the chain's joint
// springs and the storeys' dashpots, which DART integrates implicitly, and the rest of C and
// the load as external forces converge to the reference at first order, Rayleigh and modal.
// Measured: Rayleigh 3.4e-2, 8.8e-3, 2.2e-3 at N = 64, 256, 1024; modal 3.5e-2, 9.0e-3, 2.3e-3.
TEST(BuildingsDart, DefaultWithoutContactConvergesToTheReference) {
  for (const BuildingDamping damping : {BuildingDamping::rayleigh, BuildingDamping::modal}) {
    BuildingScene s = issue_scene();
    s.damping = damping;
    s.delta = 10.0;
    const std::string what = damping == BuildingDamping::modal ? "no_contact_modal" : "no_contact_rayleigh";
    const std::vector<double> e = errors(assemble(s), "default", what);
    EXPECT_LT(e[1], e[0] / 3.0) << what;
    EXPECT_LT(e[2], e[1] / 3.0) << what;
    EXPECT_LT(e[2], 3e-3) << what;
  }
}

// A step too long for the pulse fails before a run, a step cap and a time limit end a run with
// their statuses, and the registry's row solves the scene.
TEST(BuildingsDart, LimitsEndARunWithTheirStatus) {
  const BuildingModel md = assemble(issue_scene());
  Settings long_step;
  long_step.wh = 1e4;  // h far beyond the pulse's period
  const BuildingsResult too_long = dart::solve_buildings(md, long_step);
  EXPECT_EQ(too_long.status, Status::failed);
  EXPECT_EQ(too_long.events, 0);
  EXPECT_EQ(too_long.message.find('\n'), std::string::npos) << too_long.message;

  Settings cap;
  cap.step_cap = 10;
  const BuildingsResult capped = dart::solve_buildings(md, cap);
  EXPECT_EQ(capped.status, Status::step_cap) << capped.message;
  EXPECT_EQ(capped.events, 0);

  for (const char* v : {"dantzig-faithful", "default"}) {
    Settings limited;
    limited.variant = v;
    limited.steps = 4096;
    limited.time_limit = 1e-3;
    const BuildingsResult late = dart::solve_buildings(md, limited);
    EXPECT_EQ(late.status, Status::time_limit) << v << ": " << late.message;
    EXPECT_NE(late.message.find("wall time"), std::string::npos) << late.message;
    EXPECT_LT(late.events, step_count(md.t_end, late.step));
  }

  const SolverInfo* info = find_solver("dart");
  ASSERT_NE(info, nullptr);
  ASSERT_NE(info->solve_buildings, nullptr);
  const std::atomic<bool> stop{true};
  Settings stopped;
  stopped.stop = &stop;
  const BuildingsResult halted = info->solve_buildings(md, stopped);
  EXPECT_EQ(halted.status, Status::time_limit) << halted.message;
  EXPECT_NE(halted.message.find("stopped"), std::string::npos) << halted.message;
}

// An unknown variant is refused in one line, naming the variants.
TEST(BuildingsDart, UnknownVariantIsRefusedInOneLine) {
  Settings set;
  set.variant = "no-such";
  const BuildingsResult r = dart::solve_buildings(assemble(issue_scene()), set);
  EXPECT_EQ(r.status, Status::failed);
  EXPECT_NE(r.message.find("dantzig-faithful"), std::string::npos) << r.message;
  EXPECT_EQ(r.message.find('\n'), std::string::npos) << r.message;
}

}  // namespace buildings_dart_tests
}  // namespace pb
