// Siconos (solvers/siconos/) as a peer: its MoreauJeanOSI against the in-house Moreau-Jean
// stepper at equal theta, gamma and h (with the load sampled the way Siconos samples it), its
// event-driven LSODAR scheme against the event-driven reference, what its LCP driver and its
// integrators actually do with the settings given, and the library's other integrators: the
// combined projection's gaps, and the causes of the two that fail (Bilbao's left-out load,
// NewMarkAlpha's negated stiffness), measured on the linked library. Thread safety, statuses,
// restitution and convergence: the contract of every solver (solver_contract_test.cpp).
// Built only when CMake finds Siconos (tests/CMakeLists.txt).

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cases/case_set.hpp"
#include "cases/system.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/moreau_jean/moreau_jean.hpp"
#include "solvers/siconos/siconos_solver.hpp"
#include "kit/testing.hpp"
#include "solvers/registry.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace siconos_tests {

using test::make_case;
using test::sci;

Settings variant(std::string_view name) {
  Settings st;
  st.variant = std::string(name);
  return st;
}

double relative(double a, double b) { return std::abs(a - b) / std::abs(b); }

// A sample of the paper's families: every 743rd point of cases/sets/paper.toml (33 points:
// every family, pair and row3, sine and cosine, normal and reverse, eps 0, 0.5 and 1, a_p != 1,
// Pi2 from 0.1 to 5.7; 27 with impacts, 6 with a contact phase), and fig3 points 79 and 479,
// asymmetric row3 cases where both contacts are active at once with q of mixed signs, so that
// Lemke (or enumeration) runs.
std::vector<Case> paper_sample() {
  const CaseSet set = load_case_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/paper.toml");
  std::vector<Case> cases;
  for (std::size_t i = 0; i < set.cases.size(); i += 743) cases.push_back(set.cases[i]);
  cases.push_back(set.cases[79]);
  cases.push_back(set.cases[479]);
  return cases;
}

// Siconos' MoreauJeanOSI forms the load of a step from fExt at t_k and t_k+1, weighted by theta;
// moreau-jean's variant end-samples does the same with the same sampling of a_g (Pulse::sample).
// The two schemes are then the same arithmetic in a different order: Pi1, the counts and the
// monitor's measures agree to round-off on every point, whichever LCP solver Siconos uses.
TEST(Siconos, MoreauJeanOsiMatchesTheInHouseStepperWithEndSampledLoads) {
  const std::vector<Case> cases = paper_sample();
  ASSERT_EQ(cases.size(), 35u);
  Settings in_house = variant(moreau_jean::kEndSamples);
  double worst = 0.0, worst_default = 0.0;
  long lemke_runs = 0;
  for (const Case& c : cases) {
    const System s = make_system(c);
    const Result mine = moreau_jean::solve(s, in_house);
    const Result step_mean = moreau_jean::solve(s, {});
    ASSERT_EQ(mine.status, Status::ok) << mine.message;
    worst_default = std::max(worst_default, relative(step_mean.pi1, mine.pi1));
    for (std::string_view v : {"moreau-jean-lemke", "moreau-jean-enum"}) {
      siconos::LcpPaths paths;
      const Result theirs = siconos::solve_counting(s, variant(v), paths);
      ASSERT_EQ(theirs.status, Status::ok) << c.family << " " << v << ": " << theirs.message;
      lemke_runs += paths.solver;
      worst = std::max(worst, relative(theirs.pi1, mine.pi1));
      // 1e-10: the agreement asked of the two implementations; measured 4.2e-15 at most here
      // (1.6e-14 over the 23 820 points of the paper set).
      EXPECT_LT(relative(theirs.pi1, mine.pi1), 1e-10) << c.family << " pi2=" << c.pi2 << " " << v;
      EXPECT_EQ(theirs.t_max, mine.t_max) << c.family << " pi2=" << c.pi2;
      EXPECT_EQ(theirs.steps, mine.steps);
      EXPECT_EQ(theirs.impacts, mine.impacts) << c.family << " pi2=" << c.pi2;
      EXPECT_EQ(theirs.contact_phases, mine.contact_phases) << c.family << " pi2=" << c.pi2;
      EXPECT_EQ(theirs.isolated_impacts, mine.isolated_impacts);
      // The energy balance is measured from the states (StepMonitor): equal states, equal
      // excess, to the round-off of sums over a run (relative to the energy scale).
      EXPECT_NEAR(theirs.energy_excess, mine.energy_excess, 1e-12);
    }
  }
  RecordProperty("worst_relative_pi1", sci(worst));
  RecordProperty("worst_relative_pi1_against_step_mean", sci(worst_default));
  EXPECT_GT(lemke_runs, 0) << "the sample must make the LCP solver itself run";
  // The load rule is the whole difference: with moreau-jean's default (the exact step mean of
  // a_g) Pi1 differs by up to 1.1e-2 on this sample (N = 64), far above round-off.
  EXPECT_GT(worst_default, 1e-3);
}

// At a touching start (Pi3 = 0) the two implementations of the one scheme part (issue 33,
// item 5): which of them departs is round-off, not the scheme. Two bodies that the load
// presses together stay in persistent contact, where the gap is zero in exact arithmetic and
// the activation test g + gamma h g' <= 0 meets it at zero. Siconos computes the gap as
// H q + b of bodies whose displacements its LCP keeps bit for bit equal: 0, so the contact
// stays in the index set. moreau-jean forms delta - u_L + u_R from displacements each updated
// on its own: 8.7e-19 on the pair below (2e-16 of u), so the contact leaves the step, the
// bodies overlap by a step's travel and it comes back. With a gap of 1e-9 a_p / w_p^2 instead
// of 0 no gap sits at round-off and they agree to round-off again. The difference at Pi3 = 0
// is bounded by what a step of that chatter moves: measured here at most 7.4e-4 (the issue's
// campaign saw 1.6e-2 over 70 touching cases at N = 64), bounded at 2e-2.
TEST(Siconos, AtATouchingStartMoreauJeanOsiAndEndSamplesPartOnlyWhereRoundOffDecidesAContact) {
  double worst_touching = 0.0, worst_apart = 0.0;
  int differ = 0, cases = 0;
  for (Scene scene : {Scene::pair, Scene::row3})
    for (PulseShape p : {PulseShape::sine, PulseShape::cosine})
      for (Directivity d : {Directivity::normal, Directivity::reverse})
        for (double pi2 : {0.5, 1.0, 2.0})
          for (double pi5 : {0.5, 2.0})
            for (double pi3 : {0.0, 1e-9}) {
              Case c = make_case(scene, p, pi2, pi5, 0.5);
              c.directivity = d;
              c.pi3 = pi3;
              if (scene == Scene::row3) c.pi7 = pi5, c.pi8 = 1.0;
              const System s = make_system(c);
              const Result mine = moreau_jean::solve(s, variant(moreau_jean::kEndSamples));
              const Result theirs = siconos::solve(s, variant("moreau-jean-lemke"));
              ASSERT_EQ(mine.status, Status::ok) << mine.message;
              ASSERT_EQ(theirs.status, Status::ok) << theirs.message;
              const double e = relative(theirs.pi1, mine.pi1);
              if (pi3 == 0.0) {
                worst_touching = std::max(worst_touching, e);
                differ += e > 1e-10 ? 1 : 0;
                ++cases;
              } else {
                worst_apart = std::max(worst_apart, e);
              }
            }
  RecordProperty("worst_relative_pi1_touching", sci(worst_touching));
  RecordProperty("touching_cases_that_differ", std::to_string(differ) + " of " + std::to_string(cases));
  EXPECT_LT(worst_apart, 1e-10);     // the scheme, where no gap sits at round-off
  EXPECT_LT(worst_touching, 2e-2);   // a step's chatter where one does
  EXPECT_GT(differ, 0) << "the round-off this test documents no longer shows: revisit its comment";
}

// Siconos' dense LCP driver returns z = 0 without a solver when q >= 0, and z = -q / M without
// a solver when the LCP has one row; only the other calls reach Lemke or enumeration, and only
// those write the solver's iteration counter (counted independently by the solver).
TEST(Siconos, LcpDriverReachesTheSolverOnlyWithSeveralRowsAndANegativeQ) {
  const std::vector<Case> cases = paper_sample();
  const Case pair = make_case(Scene::pair, PulseShape::cosine, 0.8, 0.5, 0.5);  // 4 impacts
  for (std::string_view v : {"moreau-jean-lemke", "moreau-jean-enum"}) {
    for (const Case& c : {pair, cases[33], cases[34]}) {  // and fig3's row3 at a_p 1.962 and 9.81
      siconos::LcpPaths p;
      const Result r = siconos::solve_counting(make_system(c), variant(v), p);
      ASSERT_EQ(r.status, Status::ok) << r.message;
      EXPECT_GT(p.calls, 0);
      EXPECT_EQ(p.trivial + p.one_row + p.solver, p.calls);
      EXPECT_EQ(p.written, p.solver) << v << " " << c.family;
      if (c.scene == Scene::pair) {
        EXPECT_EQ(p.solver, 0) << "one contact: the solver never runs";
      } else {
        EXPECT_GT(p.solver, 0) << v << " " << c.family;
      }
      EXPECT_NE(r.message.find(std::to_string(p.solver) + " by"), std::string::npos) << r.message;
    }
  }
}

TEST(Siconos, MoreauJeanOsiHoldsTheThetaAndGammaGiven) {
  const System s = make_system(make_case(Scene::pair, PulseShape::cosine, 1.0, 0.5, 0.5));
  for (double theta : {0.5, 0.75, 1.0})
    for (double gamma : {0.0, 0.3, 1.0}) {
      Settings st;
      st.theta = theta;
      st.gamma = gamma;
      const siconos::MoreauJeanSetup held = siconos::moreau_jean_setup(s, st);
      EXPECT_EQ(held.theta, theta);
      EXPECT_EQ(held.gamma, gamma);
      EXPECT_TRUE(held.use_gamma) << "gamma given: the activation rule y + gamma h y' <= 0";
      EXPECT_EQ(held.activation_threshold, 0.0);
    }
}

// LsodarOSI's scalar setTol(itol, rtol, atol) of Siconos 4.4 stores rtol as atol as well; the
// solver uses the array form, and LSODAR must hold exactly the tolerances set.
TEST(Siconos, LsodarHoldsTheTolerancesSet) {
  const System s = make_system(make_case(Scene::row3, PulseShape::sine, 1.0, 0.5, 0.5));
  for (double scale : {1.0, 100.0}) {
    Settings st = variant("event-driven-lsodar");
    st.tol_scale = scale;
    const siconos::EventDrivenSetup held = siconos::event_driven_setup(s, st);
    EXPECT_EQ(held.itol, 1) << "scalar rtol and atol";
    EXPECT_EQ(held.rtol, siconos::kRtol * scale);
    EXPECT_EQ(held.atol, siconos::kAtol * scale);
    EXPECT_EQ(held.itask, 1) << "LSODAR overshoots an output time and interpolates back";
    // Siconos' own event tolerance, 1000 * 10 * DBL_EPSILON (in the pulse's units here).
    EXPECT_EQ(held.event_tolerance, 1e4 * std::numeric_limits<double>::epsilon());
  }
}

// Cases with impacts where Siconos' event-driven run goes to the end (one contact at a time,
// so Newton's law and the reference's Poisson law coincide): Pi1 within LSODAR's tolerance.
TEST(Siconos, EventDrivenMatchesTheReferenceToLsodarsTolerance) {
  struct Point {
    Scene scene;
    PulseShape pulse;
    double pi2;
  };
  const Point points[] = {
      {Scene::wall, PulseShape::sine, 0.8},   {Scene::wall, PulseShape::cosine, 1.5},
      {Scene::pair, PulseShape::sine, 1.0},   {Scene::pair, PulseShape::cosine, 0.3},
      {Scene::pair, PulseShape::cosine, 0.8}, {Scene::row3, PulseShape::sine, 1.0},
      {Scene::row3, PulseShape::cosine, 0.3}, {Scene::row3, PulseShape::cosine, 0.8},
  };
  double worst = 0.0;
  for (const Point& p : points) {
    const System s = make_system(make_case(p.scene, p.pulse, p.pi2, 0.5, 0.5));
    const Result ref = event_driven::solve(s, {});
    const Result r = siconos::solve(s, variant("event-driven-lsodar"));
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_GT(r.impacts, 0);
    EXPECT_EQ(r.impacts, ref.impacts) << name(p.scene) << " pi2=" << p.pi2;
    worst = std::max(worst, relative(r.pi1, ref.pi1));
    // 1e-8: measured 3.4e-9 at most here (rtol = atol = 1e-10 over a run, and the cubic
    // Hermite maximum between output points, ~1e-9 at T_min / 256).
    EXPECT_LT(relative(r.pi1, ref.pi1), 1e-8) << name(p.scene) << " " << name(p.pulse) << " pi2=" << p.pi2;
    // Newton's law at each isolated impact, through Siconos' impact LCP.
    if (r.isolated_impacts > 0) {
      EXPECT_NEAR(r.restitution_low, 0.5, 1e-12);
      EXPECT_NEAR(r.restitution_high, 0.5, 1e-12);
    }
  }
  RecordProperty("worst_relative_pi1", sci(worst));
}

// A sequence of impacts that accumulates (eps = 0.5, the sine pulse pressing body 0 against
// its neighbour) ends, in Siconos 4.4's event-driven scheme, with a gap that LSODAR's root
// location leaves below Siconos' absolute event tolerance, and Siconos throws. The run reports
// it as failed, with Siconos' message and the events it got through.
TEST(Siconos, EventDrivenFailsWithSiconosMessageWhereImpactsAccumulate) {
  const System s = make_system(make_case(Scene::pair, PulseShape::sine, 0.8, 0.5, 0.5));
  const Result r = siconos::solve(s, variant("event-driven-lsodar"));
  EXPECT_EQ(r.status, Status::failed);
  EXPECT_NE(r.message.find("output of level 0 must be positive"), std::string::npos) << r.message;
  EXPECT_GT(r.steps, 100) << "events before the failure are kept";
  EXPECT_GT(r.impacts, 10);
  EXPECT_TRUE(std::isnan(r.pi1));
}

// Issue 33 (9): LSODAR on a 1000-body chain under a 1 s limit took 6.3 s. Siconos' set-up is
// O(n^3) (LsodarOSI sizes its work arrays anew for every body it is given, (2i)^2 doubles
// zeroed for the i-th: 8.3 s at 1000 bodies) and ran before the run's deadline was made.
// The deadline now starts first, and the load plugin reads it once per body in the set-up
// and in every right-hand side LSODAR evaluates, inside its Fortran steps and Jacobians too.
// What a run does between two reads is at most one LU factorisation of LSODAR's 2n x 2n
// Jacobian or one Lemke LCP on the closed contacts (1.0 s for an LU at 1000 bodies, measured
// alone), so the bounds below are generous multiples of the limit, not timings.
TEST(Siconos, LsodarEndsWithinItsTimeLimitInTheSetUpAndInItsSteps) {
  const auto timed = [](const Case& c, double limit, Result& r) {
    Settings st = variant("event-driven-lsodar");
    st.time_limit = limit;
    const System s = make_system(c);
    const auto start = std::chrono::steady_clock::now();
    r = siconos::solve(s, st);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  Case big = make_case(Scene::chain, PulseShape::sine, 1.0, 1.0, 0.5);
  big.bodies = 1000;
  Result r;
  double seconds = timed(big, 0.5, r);
  EXPECT_EQ(r.status, Status::time_limit) << r.message;
  EXPECT_NE(r.message.find("in Siconos' set-up of 1000 bodies"), std::string::npos) << r.message;
  // About 0.6 s here; the bound is ten times that, for a slower or loaded machine, and still
  // under the old code's 8 s on this one.
  EXPECT_LT(seconds, 6.0) << "the old code: 8 s";
  RecordProperty("set_up_seconds", sci(seconds));
  // A stiff chain (body 0 at half the others' frequency, Pi2 = 5): LSODAR switches to BDF and
  // forms its Jacobian, so the limit passes inside the Fortran integrator's calls.
  Case stiff = make_case(Scene::chain, PulseShape::sine, 5.0, 0.5, 0.0);
  stiff.pi3 = 0.1;
  stiff.bodies = 100;
  seconds = timed(stiff, 0.5, r);
  EXPECT_EQ(r.status, Status::time_limit) << r.message;
  EXPECT_NE(r.message.find("wall time at t = "), std::string::npos) << r.message;
  EXPECT_LT(seconds, 6.0);
  RecordProperty("steps_seconds", sci(seconds));
}

// Siconos sees the case in the pulse's units, so its absolute tolerances do not move with a_p
// and w_p: Pi1 is the same at a_p = 1e-3 and 1e3 as at 1 (to round-off for the time-stepper,
// where the arithmetic is the same up to the rounding of the scaled parameters).
TEST(Siconos, Pi1DoesNotDependOnThePulseScale) {
  Case c = make_case(Scene::row3, PulseShape::cosine, 0.8, 0.5, 0.5);
  const Result base = siconos::solve(make_system(c), {});
  const Result base_ed = siconos::solve(make_system(c), variant("event-driven-lsodar"));
  ASSERT_EQ(base.status, Status::ok);
  ASSERT_EQ(base_ed.status, Status::ok);
  double worst = 0.0, worst_ed = 0.0;
  for (double a_p : {1e-3, 1e3}) {
    c.a_p = a_p;
    c.w_p = 3.7;
    const Result r = siconos::solve(make_system(c), {});
    const Result ed = siconos::solve(make_system(c), variant("event-driven-lsodar"));
    worst = std::max(worst, relative(r.pi1, base.pi1));
    worst_ed = std::max(worst_ed, relative(ed.pi1, base_ed.pi1));
    // 1e-12: the rounding of k, c, delta in the pulse's units over ~1300 steps; measured 1.3e-16.
    EXPECT_NEAR(r.pi1, base.pi1, 1e-12 * base.pi1) << "a_p=" << a_p;
    EXPECT_EQ(r.impacts, base.impacts);
    // 1e-9: LSODAR chooses its steps anew from those rounding-level differences, so Pi1 moves
    // within its tolerance (rtol = atol = 1e-10); measured 6.1e-11.
    EXPECT_NEAR(ed.pi1, base_ed.pi1, 1e-9 * base_ed.pi1) << "a_p=" << a_p;
  }
  RecordProperty("worst_relative_pi1", sci(worst));
  RecordProperty("worst_relative_pi1_event_driven", sci(worst_ed));
}

// A kicked chain starts from System::u_start, v_start: Siconos' time-stepper follows the
// in-house one (end samples) on the chain too, history row by history row.
TEST(Siconos, KickedChainStartsFromTheSystemsStartState) {
  Case c = make_case(Scene::chain, PulseShape::sine, 1.0, 0.5, 0.5);
  c.bodies = 5;
  c.kick = 2.0;
  const System s = make_system(c);
  Settings st = variant(moreau_jean::kEndSamples);
  st.history_samples = 1;
  const Result mine = moreau_jean::solve(s, st);
  st.variant = "";
  const Result theirs = siconos::solve(s, st);
  ASSERT_EQ(theirs.status, Status::ok) << theirs.message;
  ASSERT_EQ(theirs.history.rows(), mine.history.rows());
  ASSERT_EQ(theirs.history.row_size(), mine.history.row_size());
  EXPECT_GT(theirs.impacts, 4);
  EXPECT_EQ(test::HistoryRow(theirs.history, 0).v(0), s.v_start[0]);
  double worst = 0.0;
  const double scale = s.length_scale() * s.pulse.w;  // a_p / w_p, for velocities and lambda h
  for (std::size_t k = 0; k < mine.history.data.size(); ++k)
    worst = std::max(worst, std::abs(theirs.history.data[k] - mine.history.data[k]) / scale);
  RecordProperty("worst_history_difference", sci(worst));
  // 1e-11 of a_p / w_p (the velocities; displacements and gaps in a_p / w_p^2, lambda in
  // a_p): the round-off of ~1000 steps through impacts on every contact; measured 7.8e-14.
  EXPECT_LT(worst, 1e-11);
}

// MoreauJeanBilbaoOSI integrates a linear oscillator well, but its free state leaves the
// external force out (Siconos 4.4, MoreauJeanBilbaoOSI::computeFreeState: the stiffness, the
// damping and the state only). Both halves, measured: without a ground load, a kicked undamped
// body (the wall out of reach) follows the closed form of its free vibration at the step ends,
// to second order; with the load, every state equals that of the same run unloaded, and the
// run fails by name.
TEST(Siconos, BilbaoConvergesWithoutALoadAndLeavesTheGroundLoadOut) {
  System s = make_system(make_case(Scene::wall, PulseShape::sine, 0.8, 0.5, 0.5));
  s.delta = 1e3 * s.length_scale();  // no contact
  s.bodies[0].c = 0.0;
  s.u_start = {0.0};
  s.v_start = {0.5 * s.length_scale() * s.pulse.w};
  const double w = std::sqrt(s.bodies[0].k / s.bodies[0].m);
  s.pulse.amplitude = 0.0;
  Settings st = variant("bilbao");
  st.history_samples = 1;
  std::vector<double> worst;
  for (int n : {64, 512}) {
    st.steps = n;
    const Result r = siconos::solve(s, st);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    ASSERT_GT(r.history.rows(), 100u);
    double e = 0.0;
    for (std::size_t k = 0; k < r.history.rows(); ++k) {
      const test::HistoryRow row(r.history, k);
      e = std::max(e, std::abs(row.u(0) - s.v_start[0] / w * std::sin(w * row.t())) / s.length_scale());
    }
    worst.push_back(e);
    RecordProperty("displacement_error_unloaded_N" + std::to_string(n), sci(e));
  }
  // Second order: 8 times the steps, 64 times less error (measured 6.4e-4 -> 1.0e-5 a_p/w_p^2;
  // 4.1e-2 at N = 8). 1e-4 and a drop of 30: the margins of that order.
  EXPECT_LT(worst[1], 1e-4);
  EXPECT_GT(worst[0] / worst[1], 30.0);
  s.pulse.amplitude = 1.0;  // loaded again
  st.history_samples = 0;
  const Result loaded = siconos::solve(s, st);
  EXPECT_EQ(loaded.status, Status::failed);
  EXPECT_NE(loaded.message.find("left the ground load out"), std::string::npos) << loaded.message;
  EXPECT_GT(loaded.steps, 100) << "the whole run is compared with its unloaded twin";
}

// NewMarkAlphaOSI::computeW of Siconos 4.4 negates a LagrangianLinearTIDS's K and C in place on
// every call, once per Newton iteration. The run reports it from the linked library: the K and C
// a converged step left (the sine pulse, whose first step converges in one iteration), or how
// many iterations of a step that does not converge flipped body 0's K (the cosine pulse, from
// t = 0); never a Pi1.
TEST(Siconos, NewmarkAlphaFailsNamingTheStiffnessItNegated) {
  // Its run of the wall case under a pulse: failed, with no Pi1.
  const auto failed_run = [](PulseShape pulse) {
    const Result r = siconos::solve(make_system(make_case(Scene::wall, pulse, 0.8, 0.5, 0.5)), variant("newmark-alpha"));
    EXPECT_EQ(r.status, Status::failed);
    EXPECT_TRUE(std::isnan(r.pi1));
    return r;
  };
  const Result changed = failed_run(PulseShape::sine);
  EXPECT_NE(changed.message.find("after 1 events (t = 0.0981748), Newton converged on a changed system: body 0 "
                                 "holds K = -0.64, C = -0.08 instead of 0.64, 0.08"),
            std::string::npos)
      << changed.message;
  const Result looped = failed_run(PulseShape::cosine);
  // kNewtonOverrun (10) times EventDriven's own limit (50), every one of them flipping K.
  EXPECT_NE(looped.message.find("newtonSolve does not converge: 500 Newton iterations in the step from t = 0 (its "
                                "own limit is 50"),
            std::string::npos)
      << looped.message;
  EXPECT_NE(looped.message.find("K in 500 of them"), std::string::npos) << looped.message;
  EXPECT_EQ(looped.steps, 0);
}

// TimeSteppingCombinedProjection projects the positions at the end of each step: no gap is
// left below minus its tolerance (1e-10 a_p / w_p^2). TimeSteppingDirectProjection projects at
// the start of the next step, so the state at a step's end still overlaps by up to a step of
// travel, as Moreau-Jean's does.
TEST(Siconos, CombinedProjectionLeavesNoGapBelowItsTolerance) {
  double deepest = 0.0, direct_deepest = 0.0;
  for (Scene scene : {Scene::wall, Scene::pair, Scene::row3})
    for (PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
      const System s = make_system(make_case(scene, p, 0.8, 0.5, 0.5));
      const Result r = siconos::solve(s, variant("combined-projection"));
      const Result d = siconos::solve(s, variant("direct-projection"));
      ASSERT_EQ(r.status, Status::ok) << r.message;
      ASSERT_EQ(d.status, Status::ok) << d.message;
      EXPECT_GT(r.impacts, 0);
      if (std::isfinite(r.min_gap)) deepest = std::min(deepest, r.min_gap / s.length_scale());
      if (std::isfinite(d.min_gap)) direct_deepest = std::min(direct_deepest, d.min_gap / s.length_scale());
      EXPECT_NE(r.message.find("projection: "), std::string::npos) << r.message;
    }
  RecordProperty("deepest_gap_combined", sci(deepest));
  RecordProperty("deepest_gap_direct", sci(direct_deepest));
  EXPECT_GE(deepest, -siconos::kProjectionTol);
  // Up to a step of travel at N = 64: measured -6.9e-2 a_p / w_p^2 (combined: -1.1e-16).
  EXPECT_LT(direct_deepest, -1e-3);
}

// The statuses every solver reports are the contract's (solver_contract_test.cpp: step cap,
// a refused non-finite body, runaway, stop flag, time limit); Siconos' own: an unknown
// variant fails the run (the check refuses it before a sweep).
TEST(Siconos, CheckAndDescribeNameEverySetting) {
  Settings st;
  EXPECT_EQ(siconos::check(st), "");
  EXPECT_EQ(siconos::describe(st), R"({"steps":64,"theta":0.5,"gamma":0.5,"lcp":"lemke"})");
  st.variant = "moreau-jean-enum";
  st.wh = 2.0;
  st.theta = 1.0;
  EXPECT_EQ(siconos::check(st), "");
  EXPECT_EQ(siconos::describe(st), R"({"wh":2,"theta":1,"gamma":0.5,"lcp":"enum"})");
  test::expect_refused(siconos::check, st, "theta", [](Settings& s) { s.theta = 0.4; });
  test::expect_refused(siconos::check, st, "gamma", [](Settings& s) { s.gamma = 2.0; });
  // moreau-jean-enum names its solver
  test::expect_refused(siconos::check, st, "lcp", [](Settings& s) { s.lcp = "lemke"; });
  st = variant("event-driven-lsodar");
  EXPECT_EQ(siconos::check(st), "");
  EXPECT_EQ(siconos::describe(st), R"({"tol_scale":1,"rtol":1e-10,"atol":1e-10,"output":"T_min/256"})");
  test::expect_refused(siconos::check, st, "steps", [](Settings& s) { s.steps = 64; });
  test::expect_refused(siconos::check, st, "tol_scale", [](Settings& s) { s.tol_scale = 0.0; });
  st = variant("x");
  EXPECT_EQ(siconos::check(st).rfind("variant:", 0), 0u);
  st = {};
  st.step_cap = -1;  // the limits are every solver's: the registry's check applies them
  EXPECT_EQ(find_solver("siconos")->check(st).rfind("step_cap:", 0), 0u);
  // Siconos' other integrators: each names the settings it uses, its LCP solver among them.
  st = variant("schatzman-paoli");
  EXPECT_EQ(siconos::describe(st), R"({"steps":64,"theta":0.5,"lcp":"lemke"})");
  st = variant("d1-minus-linear");
  st.lcp = "enum";
  EXPECT_EQ(siconos::check(st), "");
  EXPECT_EQ(siconos::describe(st), R"({"steps":64,"lcp":"enum"})");
  st.lcp = "pgs";
  EXPECT_EQ(siconos::check(st).rfind("lcp:", 0), 0u);
  st = variant("combined-projection");
  EXPECT_EQ(siconos::describe(st), R"({"steps":64,"theta":0.5,"lcp":"lemke","mlcp":"enum",)"
                                   R"("projection_tol":1e-10,"projection_iterations":20})");
  st = variant("direct-projection");
  st.projection_tol = 1e-8;
  EXPECT_EQ(siconos::check(st), "");
  EXPECT_EQ(siconos::describe(st), R"({"steps":64,"theta":0.5,"gamma":0.5,"lcp":"lemke","mlcp":"enum",)"
                                   R"("projection_tol":1e-08,"projection_iterations":20})");
  st.projection_tol = -1.0;
  EXPECT_EQ(siconos::check(st).rfind("projection_tol:", 0), 0u);
  st = variant("schatzman-paoli");
  st.projection_tol = 1e-8;
  EXPECT_EQ(siconos::check(st).rfind("projection_tol:", 0), 0u) << "only the projections project";
  EXPECT_EQ(siconos::describe(variant("bilbao")), R"({"steps":64,"lcp":"lemke"})");
  EXPECT_EQ(siconos::describe(variant("newmark-alpha")), R"({"steps":64,"rho_infty":0.7,"lcp":"lemke"})");
  ASSERT_NE(find_solver("siconos"), nullptr);
  EXPECT_EQ(find_solver("siconos")->solve, &siconos::solve);
}

}  // namespace siconos_tests
}  // namespace pb
