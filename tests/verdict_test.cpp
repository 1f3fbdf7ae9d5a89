// The verdict on a finished run (kit/verdict.hpp): each criterion alone makes a run
// unresolved and is named; what a run did not measure is not judged; a run that did not end
// ok has none. The contract test (solver_contract_test.cpp) holds every solver to it.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "cases/system.hpp"
#include "kit/verdict.hpp"
#include "kit/testing.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace verdict_tests {

using test::kNaN;

// A run that measured nothing the verdict judges (the reference's ok run is one).
Result quiet(const System& s) {
  Result r;
  r.pi1 = 1.0;
  r.step = s.t_min / 64.0;
  return r;
}

TEST(Verdict, EachCriterionAloneMakesAFinishedRunUnresolvedAndIsNamed) {
  const System s = make_system(test::make_case(Scene::wall, PulseShape::sine, 1.0, 1.0, 0.5));
  Result r = quiet(s);
  judge(s, r);
  EXPECT_EQ(r.resolved, true);
  EXPECT_EQ(r.unresolved, "");

  struct Bad {
    const char* words;
    void (*make)(Result&, const System&);
  };
  const Bad bad[] = {
      {"its step is", [](Result& x, const System& sys) { x.step = sys.t_min / 3.9; }},
      {"a contact lasted", [](Result& x, const System&) { x.contact_steps_min = 3.0; }},
      {"it made energy", [](Result& x, const System&) { x.energy_excess = 1.01; }},
      {"its isolated impacts restituted", [](Result& x, const System&) {
         x.isolated_impacts = 2;
         x.restitution_low = 0.5;
         x.restitution_high = 0.61;
       }},
  };
  for (const Bad& b : bad) {
    Result x = quiet(s);
    b.make(x, s);
    judge(s, x);
    EXPECT_EQ(x.resolved, false) << b.words;
    EXPECT_EQ(x.unresolved.find(b.words), 0u) << x.unresolved;
  }
  // At the margins themselves: resolved.
  Result edge = quiet(s);
  edge.step = s.t_min / kMinStepsPerPeriod;
  edge.contact_steps_min = kMinContactSteps;
  edge.energy_excess = kEnergyMade;
  edge.isolated_impacts = 1;
  edge.restitution_low = edge.restitution_high = 0.5 + kRestitutionMargin / 2;
  judge(s, edge);
  EXPECT_EQ(edge.resolved, true) << edge.unresolved;
}

TEST(Verdict, WhatARunDidNotMeasureIsNotJudgedAndAFailedRunHasNone) {
  const System s = make_system(test::make_case(Scene::wall, PulseShape::sine, 1.0, 1.0, 0.5));
  Result r;
  r.pi1 = 1.0;  // no step (an event-driven or adaptive solver), nothing measured
  r.energy_excess = kNaN;
  r.contact_steps_min = kNaN;
  judge(s, r);
  EXPECT_EQ(r.resolved, true);
  // Restitution over whole contacts carries the model's response to the load (not judged).
  Result whole = quiet(s);
  whole.isolated_impacts = 1;
  whole.restitution_low = whole.restitution_high = 1.7;
  whole.restitution_over_contacts = true;
  judge(s, whole);
  EXPECT_EQ(whole.resolved, true);
  Result failed = quiet(s);
  failed.status = Status::diverged;
  failed.energy_excess = 1e6;
  judge(s, failed);
  EXPECT_FALSE(failed.resolved.has_value());
  EXPECT_EQ(failed.unresolved, "");
}

// Issue 48: a fixed-step run's error estimates (of Pi1 and of the fastest approach) above the
// target make it unresolved, each named with both percentages; at the target it is resolved.
TEST(Verdict, AnErrorEstimateAboveTheTargetMakesARunUnresolvedAndIsNamed) {
  const System s = make_system(test::make_case(Scene::wall, PulseShape::sine, 1.0, 1.0, 0.5));
  Result pi1 = quiet(s);
  pi1.error_estimate = 0.94;
  judge(s, pi1);
  EXPECT_EQ(pi1.resolved, false);
  EXPECT_EQ(pi1.unresolved.find("error estimate 94 % > target 1 %"), 0u) << pi1.unresolved;
  Result velocity = quiet(s);
  velocity.error_estimate = 0.001;
  velocity.error_estimate_velocity = 0.3;
  judge(s, velocity);
  EXPECT_EQ(velocity.resolved, false);
  EXPECT_EQ(velocity.unresolved.find("impact velocity error estimate 30 % > target 1 %"), 0u) << velocity.unresolved;
  Result edge = quiet(s);
  edge.error_estimate = edge.error_estimate_velocity = 0.05;
  judge(s, edge, {.target_error = 0.05});
  EXPECT_EQ(edge.resolved, true) << edge.unresolved;
}

// A run whose measurements were not all taken (VerdictScope::complete false: a sweep without
// --monitor, or without --estimate-error) is never resolved: not judged, unless a criterion it
// did measure fails.
TEST(Verdict, ARunWhoseMeasurementsWereNotAllTakenIsNotJudgedUnlessOneFails) {
  const System s = make_system(test::make_case(Scene::wall, PulseShape::sine, 1.0, 1.0, 0.5));
  Result r = quiet(s);
  judge(s, r, {.complete = false});
  EXPECT_FALSE(r.resolved.has_value());
  EXPECT_EQ(r.unresolved, "");
  Result coarse = quiet(s);
  coarse.step = s.t_min / 3.0;
  judge(s, coarse, {.complete = false});
  EXPECT_EQ(coarse.resolved, false);
  EXPECT_EQ(coarse.unresolved.find("its step is"), 0u) << coarse.unresolved;
}

}  // namespace verdict_tests
}  // namespace pb
