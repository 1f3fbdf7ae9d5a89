// The stress case set (cases/sets/stress.toml) through the stress study (studies/stress.hpp):
// the reference and the in-house stepper must pass its checks with the tolerances stated
// there, where their theory says they do, and Pi1 must not depend on the pulse scale.
// Where the stepper's own theory says it makes energy (theta = 1 with elastic impacts, a
// plastic impulse on a separating contact), the tests pin what it does.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "cases/case_set.hpp"
#include "cases/system.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "studies/stress.hpp"
#include "sweep/sweep.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace stress_tests {

const CaseSet& stress_set() {
  static const CaseSet set = load_case_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/stress.toml");
  return set;
}

std::vector<Case> families(std::initializer_list<const char*> names) {
  std::vector<Case> out;
  for (const Case& c : stress_set().cases)
    if (std::find_if(names.begin(), names.end(), [&](const char* n) { return c.family == n; }) != names.end())
      out.push_back(c);
  return out;
}

SettingsList moreau_jean_at(double theta, std::initializer_list<double> whs) {
  SettingsList list;
  list.reference_tol_scale = 1.0;  // the reference as users run it is what is checked here
  for (double wh : whs) {
    SweepRun run{find_solver("moreau-jean"), {}};
    run.settings.theta = theta;
    run.settings.wh = wh;
    list.runs.push_back(run);
  }
  return list;
}

bool passes(Verdict v) { return v != Verdict::fail; }

std::string what(const StressRow& row) { return row.family + " " + row.solver + " " + row.settings; }

// Every family of the stress set, the stepper from a resolved step (w_max h = 0.5) to a step
// a hundred radians long. The reference passes every check (its accuracy is none: it is the
// truth). Moreau-Jean at theta = 1/2 stays finite, within one step of travel of the gap (its
// proven bound) and restitutes eps on every isolated impact at every step; its energy
// balance stays at round-off except where the README says it cannot: a contact that still
// overlaps while it separates, under a plastic law, takes an impulse that stops it, and the
// step gains P g'/2 > 0. Its accuracy is what the step makes it.
TEST(Stress, ReferenceAndMoreauJeanPassTheChecksTheirTheoryPromises) {
  const Stress st = run_stress(stress_set().cases, moreau_jean_at(0.5, {0.5, 2, 10, 100}), {}, 1);  // one timing
  ASSERT_TRUE(st.complete);
  ASSERT_EQ(st.table.size(), 8u * 5u);  // 8 families x (the reference + 4 steps)
  for (const StressRow& row : st.table) {
    // Where every point's step is beyond the step bound (longer than the pulse: the cradle at
    // w_max h = 100), the cell has no run and no verdict.
    if (row.runs == 0) {
      EXPECT_EQ(row.finite, Verdict::none) << what(row);
      EXPECT_TRUE(row.settings.starts_with(R"({"wh":100,)")) << what(row);
      continue;
    }
    EXPECT_EQ(row.finite, Verdict::pass) << what(row);
    EXPECT_TRUE(passes(row.gap)) << what(row) << ": " << row.penetration_max << " / " << row.penetration_steps_max;
    EXPECT_TRUE(passes(row.restitution)) << what(row) << ": " << row.restitution_error_max;
    const bool theory_bounds_energy = row.solver == "event-driven" || row.settings.starts_with(R"({"wh":0.5,)") ||
                                      row.settings.starts_with(R"({"wh":100,)");
    if (theory_bounds_energy) {
      EXPECT_EQ(row.energy, Verdict::pass) << what(row) << ": " << row.energy_excess_max;
    }
    // Stable is not right: a step a hundred radians long passes the four checks above and
    // misses the response in every family, on the points where it is within the step bound
    // (the bodies faster than the pulse): 95th percentile of the Pi1 error 0.28
    // (touching-symmetric) to 2.3 (contrast-row3).
    if (row.settings.starts_with(R"({"wh":100,)")) {
      EXPECT_EQ(row.accuracy, Verdict::fail) << what(row) << ": " << row.pi1_err_p95;
      EXPECT_GT(row.pi1_err_p95, 0.25) << what(row);
    }
    // At w_max h = 0.5 the 95th percentile is 3.9 % (contrast-pair) to 16 % (cradle): half
    // the families pass (studies/stress.hpp says why the cradle never does).
    if (row.settings.starts_with(R"({"wh":0.5,)")) {
      EXPECT_LT(row.pi1_err_p95, 0.2) << what(row);
      EXPECT_EQ(row.missed_impact_points, 0u) << what(row);
      for (const char* family : {"contrast-pair", "contrast-row3", "scale", "chain-alternating"}) {
        if (row.family == family) {
          EXPECT_EQ(row.accuracy, Verdict::pass) << what(row) << ": " << row.pi1_err_p95;
        }
      }
    }
    if (row.solver == "event-driven") {
      EXPECT_EQ(row.accuracy, Verdict::none) << "the truth is not compared with itself";
    }
  }
  double plastic_worst = 0.0;
  for (const Row& r : st.runs.points) {
    if (beyond_step_bound(r.result)) continue;  // never run: no energy measured
    if (r.input.eps > 0.0) {
      EXPECT_LE(r.result.energy_excess, kEnergyTolerance) << r.input.family << " " << r.settings;
    } else {
      plastic_worst = std::max(plastic_worst, r.result.energy_excess);
    }
  }
  // Measured 2.9e-3 of the energy scale (contrast-row3, w_max h = 10): the gain is O(h)
  // per such step, and the stepper's stress report shows it.
  EXPECT_LE(plastic_worst, 1e-2);
  EXPECT_GT(plastic_worst, kEnergyTolerance);  // the mechanism is real: the check can fail
}

// Theta = 1 damps the smooth motion, but Newton's law at the step's end velocity lets a
// contact that stays closed gain energy from every step's spring and pulse impulse when
// eps = 1 (README, "theta = 1"). Plastic contacts keep the balance.
// Issue 32: penetration has one scale, a_p / w_p^2, whatever the gap. It was over delta, or
// over a_p / w_p^2 where delta = 0, and each point of the stress report's figure was the worst
// over families of both kinds: Moreau-Jean at N = 16 on a pair overlapped by 0.138 a_p / w_p^2
// touching (Pi3 = 0) and read 138 094 at Pi3 = 1e-6, for nearly the same overlap. Now the two
// agree to 0.2 % (measured 0.14 %: the gaps differ by 1e-6 a_p / w_p^2), and the gap check's
// per-step overlap is the same overlap over h max|g'|.
TEST(Stress, PenetrationHasOneScaleWhateverTheGap) {
  Settings st;
  st.steps = 16;
  double depth[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    Case c;
    c.scene = Scene::pair;
    c.pi2 = 1.0;
    c.pi3 = k == 0 ? 0.0 : 1e-6;
    c.pi5 = 0.5;
    c.eps = 0.5;
    const Row row = run_point(c, 0, *find_solver("moreau-jean"), st);
    ASSERT_EQ(row.result.status, Status::ok) << row.result.message;
    depth[k] = penetration(row);
    EXPECT_EQ(depth[k], -min_gap_ratio(row));
    EXPECT_NEAR(row.penetration_steps, -row.result.min_gap / (row.result.step * row.result.gap_rate_max), 1e-15);
  }
  EXPECT_GT(depth[0], 0.1);
  EXPECT_NEAR(depth[1], depth[0], 2e-3 * depth[0]);
}

TEST(Stress, MoreauJeanThetaOneMakesEnergyOnlyWithElasticContacts) {
  const Stress st = run_stress(families({"touching", "cradle"}), moreau_jean_at(1.0, {0.5, 2}), {});
  ASSERT_TRUE(st.complete);
  double elastic_worst = 0.0;
  for (const Row& r : st.runs.points) {
    ASSERT_EQ(r.result.status, Status::ok) << r.input.family << " " << r.settings << ": " << r.result.message;
    if (r.input.eps == 0.0) {
      EXPECT_LE(r.result.energy_excess, kEnergyTolerance) << r.input.family << " " << r.settings;
    } else {
      elastic_worst = std::max(elastic_worst, r.result.energy_excess);
    }
  }
  // Measured 3.5 energy scales (a 10-body cradle at w_max h = 2): no round-off effect.
  EXPECT_GT(elastic_worst, 0.1);
}

TEST(Stress, Pi1DoesNotDependOnThePulseScaleFrom1eMinus3To1e3) {
  for (const auto& [solver, steps] : {std::pair{"event-driven", 0}, std::pair{"moreau-jean", 64}}) {
    Settings st;
    st.steps = steps;
    std::map<std::tuple<int, double, double, double>, std::pair<double, double>> range;  // min, max
    for (const Case& c : families({"scale"})) {
      const double pi1 = find_solver(solver)->solve(make_system(c), st).pi1;
      auto [it, fresh] = range.try_emplace({static_cast<int>(c.pulse), c.eps, c.pi5, c.pi2}, pi1, pi1);
      it->second = {std::min(it->second.first, pi1), std::max(it->second.second, pi1)};
    }
    ASSERT_FALSE(range.empty());
    for (const auto& [key, mm] : range) {
      // Measured 5e-15 (reference) and 2e-15 (stepper): round-off of the scaling alone.
      EXPECT_LE(mm.second - mm.first, 1e-12 * mm.second) << solver << " pi2=" << std::get<3>(key);
    }
  }
}

}  // namespace stress_tests
}  // namespace pb
