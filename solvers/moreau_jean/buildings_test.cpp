// Moreau-Jean on the buildings scene (solvers/moreau_jean/buildings.hpp) against the exact
// reference (solvers/buildings_reference/) as the step shrinks, against the single
// oscillators' Moreau-Jean on one storey, and against its own exact properties: the
// contact-free trapezoidal rule's second order, self-similarity, no allocation in the loop.
//
// Errors are relative, the largest over every floor's peak |u| (or every storey's peak drift)
// of every building, at N = 64, 128, ..., 4096 steps per shortest period. With impacts the
// scheme is first order, and a single case's error moves erratically from one N to the next
// (where an impact falls within its step decides it: README.md, "Accuracy"), so the tests
// assert that the error falls by a margin from the coarse steps to the fine ones, and state
// the measured errors and the fitted order (test::observed_order) beside them.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "cases/buildings.hpp"
#include "cases/record.hpp"
#include "cases/system.hpp"
#include "kit/testing.hpp"
#include "kit/testing_buildings.hpp"
#include "solvers/buildings_reference/reference.hpp"
#include "solvers/moreau_jean/allocation_counter.hpp"
#include "solvers/moreau_jean/buildings.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace buildings_mj_tests {

using buildings::BuildingsResult;
using test::issue_scene;
using test::issue_scene_under_a_record;

BuildingsResult run_mj(const BuildingModel& md, int steps) {
  Settings set;
  set.steps = steps;
  return moreau_jean::solve_buildings(md, set);
}

BuildingsResult reference(const BuildingModel& md) {
  const BuildingsResult ref = buildings::solve(md);
  EXPECT_EQ(ref.status, Status::ok) << ref.message;
  return ref;
}

// The largest relative errors over every floor's peak |u| and every storey's peak |drift|.
struct PeakErrors {
  double floor = 0.0, drift = 0.0;
};

PeakErrors peak_errors(const BuildingsResult& r, const BuildingsResult& ref) {
  PeakErrors e;
  for (std::size_t b = 0; b < ref.floor_peak.size(); ++b)
    for (std::size_t i = 0; i < ref.floor_peak[b].size(); ++i) {
      e.floor = std::max(e.floor, test::rel(r.floor_peak[b][i], ref.floor_peak[b][i]));
      e.drift = std::max(e.drift, test::rel(r.drift_peak[b][i], ref.drift_peak[b][i]));
    }
  return e;
}

// The errors at N = 64, 128, ..., 4096 (seven halvings of the step).
struct Convergence {
  std::vector<double> floor, drift;
  // The largest error over the two coarsest steps, and over the two finest: a fall between
  // them that one erratic N cannot fake.
  static double coarse(const std::vector<double>& e) { return std::max(e[0], e[1]); }
  static double fine(const std::vector<double>& e) { return std::max(e[e.size() - 2], e.back()); }
};

Convergence convergence(const BuildingModel& md) {
  const BuildingsResult ref = reference(md);
  Convergence c;
  for (int n = 64; n <= 4096; n *= 2) {
    const BuildingsResult r = run_mj(md, n);
    EXPECT_EQ(r.status, Status::ok) << r.message;
    const PeakErrors e = peak_errors(r, ref);
    c.floor.push_back(e.floor);
    c.drift.push_back(e.drift);
  }
  return c;
}

// The issue's pair with its 30 mm gap: four impacts, at floors 2 and 3, alone each.
// Measured: floor peaks 6.2e-3, 3.0e-3, 1.4e-3, 8.5e-4, 4.2e-4, 1.3e-4, 1.1e-4 (order 0.99);
// storey drifts 5.3e-2 .. 1.5e-3 (order 1.06), the worst the stiff building's top storey,
// whose drift peaks at the floor-2 impact: a kink that step ends sample to O(h), erratically
// (5.9e-4 at N = 1024, 1.5e-3 at 4096, 3.7e-6 at 8192).
TEST(BuildingsMoreauJean, ConvergesToTheReferenceOnTheIssuePair) {
  const BuildingModel md = assemble(issue_scene());
  const Convergence c = convergence(md);
  EXPECT_LT(Convergence::fine(c.floor), Convergence::coarse(c.floor) / 20.0);
  EXPECT_LT(Convergence::fine(c.drift), Convergence::coarse(c.drift) / 10.0);
  EXPECT_GT(test::observed_order(c.floor), 0.8);
  EXPECT_LT(c.floor.back(), 3e-4);
  // The impacts are the reference's, each seen within two steps of its time (measured up to
  // 1.5 h), approaching at the reference's speed to O(h), erratically again (the gap rate at
  // the start of the step it entered in: floor 2's 5.4e-3 at N = 256, 1.0e-4 at 2048, 1.2e-3 at
  // 4096, 1.7e-5 at 32768).
  const BuildingsResult ref = reference(md);
  for (int n : {256, 4096}) {
    const BuildingsResult r = run_mj(md, n);
    for (std::size_t j = 0; j < ref.contacts.size(); ++j) {
      EXPECT_EQ(r.contacts[j].impacts, ref.contacts[j].impacts) << "floor " << j + 1 << ", N " << n;
      if (ref.contacts[j].impacts == 0) continue;
      EXPECT_NEAR(r.contacts[j].first_impact, ref.contacts[j].first_impact, 2.0 * r.step) << "floor " << j + 1;
      EXPECT_NEAR(r.contacts[j].impact_velocity_max / ref.contacts[j].impact_velocity_max, 1.0, n == 4096 ? 2e-3 : 1e-2);
    }
  }
}

// Impacts at several floors at once. With no gap the floors touch at rest; they part, and
// close again at every floor within 2 ms of each other (t = 0.617 s), and at N = 256 all
// three contacts enter the index set, approaching, in the one step ending at t = 1.325 s:
// Newton's law over three contacts (Lemke). Measured: floor peaks 4.7e-5 at N = 64 to 1.3e-8
// at 4096, drifts 1.3e-4 to 3.1e-8 (order 2.0: no peak sits at an impact's kink). With a 5 mm
// gap a floor hits while the others are held closed (floors stick: the reference counts
// contact phases), and the LCP is over the closed and the closing contacts: floor peaks 3.1e-4,
// 3.6e-4, 7.7e-5, 1.3e-4, 5.3e-5, 1.9e-5, 1.6e-5, drifts 7.0e-4 to 4.6e-5 (order 0.7).
TEST(BuildingsMoreauJean, ConvergesToTheReferenceWhereFloorsImpactTogether) {
  BuildingScene touching = issue_scene();
  touching.delta = 0.0;
  const Convergence t = convergence(assemble(touching));
  EXPECT_LT(Convergence::fine(t.floor), Convergence::coarse(t.floor) / 300.0);
  EXPECT_LT(Convergence::fine(t.drift), Convergence::coarse(t.drift) / 300.0);
  EXPECT_GT(test::observed_order(t.drift), 1.5);
  EXPECT_LT(t.drift.back(), 1e-6);

  BuildingScene sticking = issue_scene();
  sticking.delta = 0.005;
  const Convergence s = convergence(assemble(sticking));
  EXPECT_LT(Convergence::fine(s.floor), Convergence::coarse(s.floor) / 5.0);
  EXPECT_LT(Convergence::fine(s.drift), Convergence::coarse(s.drift) / 5.0);
  EXPECT_LT(s.floor.back(), 1e-4);
}

// Three buildings with modal damping (W_hat dense per building; the middle one touches both
// neighbours). Measured: floor peaks 6.7e-3 at N = 64 to 8.7e-5 at 4096, drifts 8.3e-3 to
// 3.6e-4 (order 0.74).
TEST(BuildingsMoreauJean, ConvergesToTheReferenceOnThreeModallyDampedBuildings) {
  BuildingScene s = issue_scene();
  s.buildings.push_back(test::building({1e5, 1.2e5}, {1.5e8, 1.4e8}));
  s.damping = BuildingDamping::modal;
  s.delta = 0.01;
  const Convergence c = convergence(assemble(s));
  EXPECT_LT(Convergence::fine(c.floor), Convergence::coarse(c.floor) / 10.0);
  EXPECT_LT(Convergence::fine(c.drift), Convergence::coarse(c.drift) / 8.0);
  EXPECT_LT(c.floor.back(), 5e-4);
}

// A record, linear between its samples: the step means of its trapezoids, as the single
// oscillators take it; the step rule `record` (steps_per_sample) puts its samples on step ends.
// Measured: floor peaks 4.4e-3 at N = 64, 3.0e-5 at 4096; 2.0e-4 with 8 steps a sample.
TEST(BuildingsMoreauJean, ConvergesToTheReferenceUnderARecord) {
  const BuildingScene s = issue_scene_under_a_record();
  const BuildingModel md = assemble(s);
  const BuildingsResult ref = reference(md);
  const PeakErrors coarse = peak_errors(run_mj(md, 64), ref), fine = peak_errors(run_mj(md, 4096), ref);
  EXPECT_LT(fine.floor, coarse.floor / 10.0);
  EXPECT_LT(fine.floor, 1e-3);
  Settings per_sample;
  per_sample.steps = 1024;
  per_sample.steps_per_sample = 8;
  const BuildingsResult r = moreau_jean::solve_buildings(md, per_sample);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_DOUBLE_EQ(r.step, record_step(*s.pulse.record, md.t_min / 1024, 8));
  EXPECT_LT(peak_errors(r, ref).floor, 1e-3);
}

// Without contact the step is the trapezoidal rule (theta = 1/2) and the load its exact step
// mean: second order, and the step ends sample each smooth peak to O(h^2). Measured: floor
// peaks 7.3e-5 at N = 64 to 1.5e-8 at 4096, drifts 1.1e-4 to 2.9e-8, order 1.99 both.
TEST(BuildingsMoreauJean, NoContactResponseIsTheReferencesToSecondOrder) {
  BuildingScene s = issue_scene();
  s.no_contact = true;
  const Convergence c = convergence(assemble(s));
  EXPECT_GT(test::observed_order(c.floor), 1.9);
  EXPECT_GT(test::observed_order(c.drift), 1.9);
  EXPECT_LT(c.floor.back(), 5e-8);
  EXPECT_LT(c.drift.back(), 1e-7);
}

// Self-similarity: a uniform pair in Pi terms at two pulse scales. The step is a fixed
// fraction of T_p (t_min / N, t_min a fixed fraction of it), and nothing in the loop is an
// absolute tolerance, so the floor peaks over a_p / w_p^2 are the same. Scaled by powers of
// two every rounding is the same and so is every bit (the gap of 0 too, where the activation
// test sits on its threshold); at another scale they agree to round-off (measured 9e-16).
TEST(BuildingsMoreauJean, FloorPeaksOverTheLengthScaleAreTheSameAtAnyPulseScale) {
  for (PulseShape shape : {PulseShape::sine, PulseShape::cosine})
    for (double pi3 : {0.0, 0.3}) {
      const auto model = [&](double a_p, double w_p) {
        BuildingScene s = uniform_pair(3, 5, 0.6, pi3, 0.5, 1.5, 0.8, Pulse(shape, a_p, w_p), a_p, w_p);
        s.xi = 0.04;
        return assemble(s);
      };
      const BuildingModel a = model(1.0, 1.0), b = model(4.0, 0.5), c = model(3.7, 12.566);
      const BuildingsResult ra = run_mj(a, 64), rb = run_mj(b, 64), rc = run_mj(c, 64);
      for (std::size_t bd = 0; bd < 2; ++bd)
        for (std::size_t i = 0; i < ra.floor_peak[bd].size(); ++i) {
          const double x = ra.floor_peak[bd][i] / a.length_scale();
          EXPECT_EQ(rb.floor_peak[bd][i] / b.length_scale(), x) << "building " << bd << " floor " << i + 1;
          EXPECT_EQ(rb.drift_peak[bd][i] / b.length_scale(), ra.drift_peak[bd][i] / a.length_scale());
          if (pi3 > 0.0) {
            EXPECT_NEAR(rc.floor_peak[bd][i] / c.length_scale(), x, 1e-12 * x);
          }
        }
      for (std::size_t j = 0; j < ra.contacts.size(); ++j) {
        EXPECT_EQ(rb.contacts[j].impacts, ra.contacts[j].impacts);
        EXPECT_EQ(rb.contacts[j].first_impact * b.w_p, ra.contacts[j].first_impact * a.w_p);
        if (pi3 > 0.0) {
          EXPECT_EQ(rc.contacts[j].impacts, ra.contacts[j].impacts);
        }
      }
    }
}

// The single oscillators' pair as two one-storey buildings.
BuildingScene scene_of(const System& sys) {
  BuildingScene s;
  for (const Body& b : sys.bodies) s.buildings.push_back(test::building({b.m}, {b.k}));
  s.xi = sys.xi;
  s.delta = sys.delta;
  s.eps = sys.eps;
  s.pulse = sys.pulse;
  s.a_p = sys.a_p;
  s.w_p = sys.pulse.w;
  s.t_end = sys.t_end;
  return s;
}

// Body i's peak |u| over the rows of a run's history.
double history_peak(const History& h, int body) {
  double peak = 0.0;
  for (std::size_t row = 0; row < h.rows(); ++row)
    peak = std::max(peak, std::abs(h.data[row * static_cast<std::size_t>(h.row_size()) + 1 + static_cast<std::size_t>(body)]));
  return peak;
}

// One storey each: the same scheme as the single oscillators' Moreau-Jean (M_hat scalar per
// body, the same load, activation, impact law and step count), in other arithmetic (an LDL^T
// solve where that one multiplies precomputed coefficients), so the two agree to round-off:
// measured 3.6e-14 over these 216 runs. A gap of 0 is left out: there every step of contact
// sits on the activation threshold g + gamma h g' = 0, where that round-off decides.
TEST(BuildingsMoreauJean, OneStoreyPairIsTheSingleOscillatorsMoreauJean) {
  double worst = 0.0;
  int compared = 0;
  for (PulseShape shape : {PulseShape::sine, PulseShape::cosine})
    for (double pi2 : {0.3, 1.0, 2.5})
      for (double pi3 : {0.2, 2.0})
        for (double pi5 : {0.5, 1.33, 4.0})
          for (double eps : {0.0, 0.6, 1.0})
            for (int n : {64, 256}) {
              Case c = test::make_case(Scene::pair, shape, pi2, pi5, eps);
              c.pi3 = pi3;
              c.a_p = 2.0;
              c.w_p = 7.0;
              const System sys = make_system(c);
              Settings set;
              set.steps = n;
              set.history_samples = 1;
              const Result single = moreau_jean::solve(sys, set);
              ASSERT_EQ(single.status, Status::ok) << single.message;
              set.history_samples = 0;
              const BuildingsResult r = moreau_jean::solve_buildings(assemble(scene_of(sys)), set);
              ASSERT_EQ(r.status, Status::ok) << r.message;
              for (int b = 0; b < 2; ++b) {
                const double e = std::abs(r.floor_peak[static_cast<std::size_t>(b)][0] / history_peak(single.history, b) - 1.0);
                EXPECT_LT(e, 1e-10) << "pi2 " << pi2 << " pi3 " << pi3 << " pi5 " << pi5 << " eps " << eps << " N " << n;
                worst = std::max(worst, e);
              }
              EXPECT_EQ(r.contacts[0].impacts, single.impacts);
              EXPECT_EQ(r.events, single.steps);
              if (single.impacts > 0) {
                EXPECT_EQ(r.contacts[0].first_impact, single.first_impact);
              }
              ++compared;
            }
  EXPECT_EQ(compared, 216);
  EXPECT_LT(worst, 1e-12);  // measured 3.6e-14
}

// The stress family's 20 + 20 storey pair, plastic impacts on floors touching at rest: it runs
// to the end, every floor moves, and its peaks are the reference's within the first-order
// error of N = 64 (measured 2.4e-4 floors, 3.5e-4 drifts).
TEST(BuildingsMoreauJean, TwentyStoreyPairRunsAndConverges) {
  const Pulse pulse(PulseShape::sine, 1.0, 1.0);
  const BuildingModel md = assemble(uniform_pair(20, 20, 0.5, 0.0, 0.0, 2.0, 1.0, pulse, 1.0, 1.0));
  ASSERT_EQ(md.contacts.size(), 20u);
  const BuildingsResult r = run_mj(md, 64);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  long impacts = 0;
  for (const buildings::ContactResult& c : r.contacts) impacts += c.impacts;
  EXPECT_GT(impacts, 20);
  for (const auto& building : r.floor_peak)
    for (double x : building) EXPECT_GT(x, 0.0);
  const PeakErrors e = peak_errors(r, reference(md));
  EXPECT_LT(e.floor, 2e-3);
  EXPECT_LT(e.drift, 2e-3);
}

TEST(BuildingsMoreauJean, LimitsEndARunWithTheirStatus) {
  const BuildingModel md = assemble(issue_scene());
  Settings cap;
  cap.step_cap = 10;
  const BuildingsResult capped = moreau_jean::solve_buildings(md, cap);
  EXPECT_EQ(capped.status, Status::step_cap);
  EXPECT_EQ(capped.events, 0);
  EXPECT_NE(capped.message.find("more than the cap 10"), std::string::npos) << capped.message;

  Settings limited;
  limited.steps = 4096;  // 1e5 steps: the clock is read after the first chunk of them
  limited.time_limit = 1e-9;
  const BuildingsResult late = moreau_jean::solve_buildings(md, limited);
  EXPECT_EQ(late.status, Status::time_limit);
  EXPECT_NE(late.message.find("more than 1e-09 s of wall time"), std::string::npos) << late.message;
  EXPECT_GT(late.events, 0);
  EXPECT_LT(late.events, step_count(md.t_end, late.step));

  const std::atomic<bool> stop{true};
  Settings stopped;
  stopped.steps = 4096;  // looked at between chunks of steps: a run of one chunk ends first
  stopped.stop = &stop;
  const BuildingsResult halted = moreau_jean::solve_buildings(md, stopped);
  EXPECT_EQ(halted.status, Status::time_limit);
  EXPECT_NE(halted.message.find("stopped"), std::string::npos) << halted.message;
}

TEST(BuildingsMoreauJean, SettingsItCannotUseAreRefusedInOneLine) {
  const BuildingModel md = assemble(issue_scene());
  Settings per_sample;
  per_sample.steps_per_sample = 4;  // a record's rule, on a pulse
  const BuildingsResult r = moreau_jean::solve_buildings(md, per_sample);
  EXPECT_EQ(r.status, Status::failed);
  EXPECT_TRUE(r.message.starts_with("steps_per_sample: the step rule `record` needs a record's samples")) << r.message;
  Settings bad;
  bad.theta = 0.3;
  EXPECT_EQ(moreau_jean::solve_buildings(md, bad).message, "theta: must be in [0.5, 1]");
  bad = {};
  bad.variant = "modal";
  EXPECT_TRUE(moreau_jean::solve_buildings(md, bad).message.starts_with("variant: unknown 'modal'"));
  Settings long_step;
  long_step.wh = 100.0;  // w_max h = 100: a step longer than the pulse period
  const BuildingsResult far = moreau_jean::solve_buildings(md, long_step);
  EXPECT_EQ(far.status, Status::failed);
  EXPECT_TRUE(far.message.starts_with(kStepBoundMessage)) << far.message;
  EXPECT_NE(far.message.find("longer than the pulse period"), std::string::npos) << far.message;
  for (const std::string& message : {r.message, far.message}) EXPECT_EQ(message.find('\n'), std::string::npos);
}

// Both load rules apply to the scene (the variants: the step mean, the default, and Siconos'
// end samples). On the sine pulse, which ends at zero, both are second order without contact:
// the end samples measured 7.4e-5 at N = 64 and 2.6e-7 at 1024.
TEST(BuildingsMoreauJean, EndSampledLoadRunsTheSameScheme) {
  BuildingScene s = issue_scene();
  s.no_contact = true;
  const BuildingModel md = assemble(s);
  const BuildingsResult ref = reference(md);
  Settings ends;
  ends.variant = std::string(moreau_jean::kEndSamples);
  for (int n : {64, 1024}) {
    ends.steps = n;
    const BuildingsResult r = moreau_jean::solve_buildings(md, ends);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_LT(peak_errors(r, ref).floor, n == 64 ? 5e-4 : 5e-6);
  }
}

// The step loop allocates nothing: a run's allocations (the scheme, the workspaces, the result)
// do not depend on its step count, with impacts alone, floors that stick, three contacts
// closing in one step (Lemke's path) and dense per-building factors (modal damping).
TEST(BuildingsMoreauJean, StepLoopNeverAllocates) {
  std::vector<BuildingModel> models;
  for (double gap : {0.03, 0.005, 0.0}) {
    BuildingScene s = issue_scene();
    s.delta = gap;
    models.push_back(assemble(s));
  }
  BuildingScene modal = issue_scene();
  modal.damping = BuildingDamping::modal;
  modal.buildings.push_back(test::building({1e5, 1.2e5}, {1.5e8, 1.4e8}));
  models.push_back(assemble(modal));
  for (const BuildingModel& md : models) {
    long few = 0, many = 0;
    {
      test::AllocationCounter counter;
      (void)run_mj(md, 64);
      few = counter.count();
    }
    {
      test::AllocationCounter counter;
      (void)run_mj(md, 1024);
      many = counter.count();
    }
    EXPECT_EQ(few, many) << "gap " << md.scene.delta;
  }
}

}  // namespace buildings_mj_tests
}  // namespace pb
