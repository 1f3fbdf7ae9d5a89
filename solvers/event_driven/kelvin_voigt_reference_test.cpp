// The exact solution of the Kelvin-Voigt model (event-driven --contact kelvin-voigt,
// solvers/event_driven/kelvin_voigt.*): what it must get exactly right whatever integrates
// it, the rigid limit it tends to, and what it refuses. Its agreement with CVODE on the same
// element is in compliant_test.cpp (CVODE is optional); the checks every solver passes are in
// solver_contract_test.cpp.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

#include "cases/system.hpp"
#include "kit/contact_elements/contact_law.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/event_driven/kelvin_voigt.hpp"
#include "kit/testing.hpp"
#include "solvers/registry.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace kelvin_voigt_reference_tests {

using test::make_case;
using test::sci;

Settings kelvin_voigt(double K) {
  Settings st;
  st.contact = event_driven::kKelvinVoigtContact;
  st.stiffness = K;
  return st;
}

using test::rel;

// A body with neither spring nor dashpot, no load, thrown at the wall at speed v: one
// contact with the element alone, half a damped oscillation, after which it leaves at
// exactly -eps v (the unclamped element's textbook zeta). Only where the release is located
// may differ: to the floor, 1e-13 T_min, over which the dashpot moves the rate by about
// 2 zeta w_c 1e-13 T_min of itself (measured 1.6e-12 and 4.9e-12 at eps 0.3 and 0.5).
// (eps = 0 is left out: the element alone is then critically damped, its two modes one
// defective mode, and the free body never leaves: the reference's modal bound cannot hold a
// defective stiff mode, and the plain one halves its stretches as the penetration decays.
// Every body of a case has a spring, which keeps the contact's modes apart.)
TEST(KelvinVoigtReference, AFreeBodyThrownAtTheWallLeavesAtEpsTimesItsSpeed) {
  for (double eps : {0.3, 0.5, 1.0}) {
    System s = make_system(make_case(Scene::wall, PulseShape::sine, 1.0, 1.0, eps));
    s.bodies[0].k = s.bodies[0].c = 0.0;
    s.pulse.amplitude = 0.0;
    s.u_start = {0.0};
    s.v_start = {-2.0 * s.a_p / s.pulse.w};
    const Result r = event_driven::solve(s, kelvin_voigt(1e4));
    ASSERT_EQ(r.status, Status::ok) << r.message;
    ASSERT_EQ(r.isolated_impacts, 1) << "eps " << eps;
    RecordProperty("restitution_error_eps" + sci(eps), sci(std::abs(r.restitution_low - eps)));
    EXPECT_NEAR(r.restitution_low, eps, 1e-10) << "eps " << eps;
    // The deepest penetration of the undamped element (eps = 1) is v / w_c exactly.
    if (eps == 1.0) {
      const double k = 1e4 * s.bodies[0].m * 1.0;  // K m0 w0^2 with w0 = Pi2 w_p = 1
      EXPECT_NEAR(-r.min_gap, 2.0 * s.a_p / s.pulse.w / std::sqrt(k / s.bodies[0].m), 1e-12);
      // Its largest force, k times that penetration, the rows' contact_force_max (issue 35):
      // taken at the ends of the stretches, so below the peak by the force's curvature over
      // the nearest end's distance from it (measured 1.4e-16 here, where a stretch ends at the peak; 1e-6 leaves room for a sampled one).
      const double f = k * 2.0 * s.a_p / s.pulse.w / std::sqrt(k / s.bodies[0].m);
      RecordProperty("contact_force_max_error", sci(rel(r.contact_force_max, f)));
      EXPECT_NEAR(r.contact_force_max, f, 1e-6 * f);
    }
  }
}

// Where no gap ever closes the element never acts, and the motion is the bodies' alone: the
// rigid reference's no-contact answer, exact at, near and away from an undamped resonance
// (the closed form's secular t sin w t), to round-off.
TEST(KelvinVoigtReference, WithoutContactItIsTheExactFreeMotionAtAndNearResonance) {
  for (double pi2 : {0.5, 1.0 - 1e-9, 1.0, 2.0})
    for (double xi : {0.0, 0.05}) {
      Case c = make_case(Scene::pair, PulseShape::cosine, pi2, 0.5, 0.5);
      c.pi3 = 1e3;  // no gap closes
      c.xi = xi;
      const System s = make_system(c);
      const Result kv = event_driven::solve(s, kelvin_voigt(1e6));
      ASSERT_EQ(kv.status, Status::ok) << kv.message;
      EXPECT_EQ(kv.impacts, 0);
      const double free = event_driven::no_contact_pi1(s);
      EXPECT_LT(rel(kv.pi1, free), 1e-11) << "pi2 " << pi2 << " xi " << xi << ": " << kv.pi1 << " vs " << free;
    }
}

// Pi1 depends on the Pi terms alone, the stiffness K included: two pulse scales solve the
// same dimensionless problem, to the reference's own accuracy.
TEST(KelvinVoigtReference, Pi1IsSelfSimilarWithTheStiffnessAsAPiTerm) {
  for (Scene scene : {Scene::wall, Scene::pair, Scene::row3}) {
    Case c = make_case(scene, PulseShape::sine, 0.7, 0.5, 0.5);
    const Result unit = event_driven::solve(make_system(c), kelvin_voigt(1e5));
    c.a_p = 9.81;
    c.w_p = 5.0;
    const Result scaled = event_driven::solve(make_system(c), kelvin_voigt(1e5));
    ASSERT_EQ(unit.status, Status::ok) << unit.message;
    ASSERT_EQ(scaled.status, Status::ok) << scaled.message;
    EXPECT_EQ(unit.impacts, scaled.impacts);
    RecordProperty(std::string(name(scene)) + "_relative_difference", sci(rel(scaled.pi1, unit.pi1)));
    EXPECT_LT(rel(scaled.pi1, unit.pi1), 1e-10) << name(scene);
  }
}

// The model error against the rigid answer falls as the stiffness grows, about as K^(-1/2)
// (the contact's duration): at least 5 times per factor 100 (measured 7 to 10), and the
// deepest penetration about 10 times (v / w_c).
TEST(KelvinVoigtReference, ApproachesTheRigidReferenceAsTheStiffnessGrows) {
  for (Scene scene : {Scene::wall, Scene::pair}) {
    const Case c = make_case(scene, PulseShape::sine, 0.5, 0.5, 0.5);
    const Result rigid = event_driven::solve(make_system(c), Settings{});
    ASSERT_EQ(rigid.status, Status::ok);
    double last = 1.0, depth = 1.0;
    for (double K : {1e4, 1e6, 1e8}) {
      const Result r = event_driven::solve(make_system(c), kelvin_voigt(K));
      ASSERT_EQ(r.status, Status::ok) << r.message;
      const double e = rel(r.pi1, rigid.pi1);
      RecordProperty(std::string(name(scene)) + "_error_K" + sci(K), sci(e));
      EXPECT_LT(e, last / 5.0) << name(scene) << " K " << K;
      EXPECT_LT(-r.min_gap, depth / 5.0) << name(scene) << " K " << K;
      last = e;
      depth = -r.min_gap;
    }
  }
}

// The history is the model's: each gap is its bodies' displacements and delta, and each
// element's force is k p + c q while the gap is closed, nothing while it is open.
TEST(KelvinVoigtReference, HistoryGapsAndForcesAreTheElementsOwn) {
  const System s = make_system(make_case(Scene::pair, PulseShape::sine, 0.8, 0.5, 0.5));
  Settings st = kelvin_voigt(1e3);
  st.history_samples = 4001;
  const Result r = event_driven::solve(s, st);
  ASSERT_EQ(r.status, Status::ok) << r.message;
  ASSERT_GT(r.impacts, 0);
  const History& h = r.history;
  ASSERT_EQ(h.rows(), 4001u);
  const compliant::Law law = compliant::make_law(compliant::Model::kelvin_voigt, 1e3 * s.bodies[1].m * s.bodies[1].w * s.bodies[1].w,
                                                 s.eps, s.bodies[0].m, s.bodies[1].m);
  int pushing = 0;
  double u_max = 0.0;
  for (std::size_t i = 0; i < h.rows(); ++i) {
    const double* row = &h.data[i * static_cast<std::size_t>(h.row_size())];
    const double u1 = row[1], u0 = row[2], v1 = row[3], v0 = row[4], g = row[5], f = row[6];
    const double scale = s.length_scale();
    EXPECT_NEAR(g, s.delta + u0 - u1, 1e-12 * scale) << "t " << row[0];
    if (g < 0.0) {
      EXPECT_NEAR(f, law.k * -g + law.c * -(v0 - v1), 1e-9 * law.k * scale) << "t " << row[0];
      ++pushing;
    } else {
      EXPECT_EQ(f, 0.0) << "t " << row[0];
    }
    u_max = std::max(u_max, std::abs(u0));
  }
  EXPECT_GT(pushing, 0);
  // Pi1 is the largest |u0| of the motion, which the samples see from below.
  EXPECT_LE(s.pi1(u_max), r.pi1 * (1 + 1e-12));
  EXPECT_GT(s.pi1(u_max), r.pi1 * (1 - 1e-3));
}

TEST(KelvinVoigtReference, RefusesMoreBodiesThanItsMatrixHolds) {
  Case c = make_case(Scene::chain, PulseShape::sine, 1.0, 0.5, 0.5);
  c.bodies = event_driven::kMaxKelvinVoigtBodies + 1;
  const Result r = event_driven::solve(make_system(c), kelvin_voigt(1e4));
  EXPECT_EQ(r.status, Status::failed);
  EXPECT_NE(r.message.find("at most"), std::string::npos) << r.message;
  c.bodies = event_driven::kMaxKelvinVoigtBodies;
  c.n_free = 0.5;
  c.pi3 = 50.0;  // gaps no body closes: the largest matrix, without the contacts' cost (minutes under ASan)
  EXPECT_EQ(event_driven::solve(make_system(c), kelvin_voigt(1e4)).status, Status::ok);
}

TEST(KelvinVoigtReference, CheckNamesTheBadSetting) {
  Settings st;
  st.contact = "hertz";
  EXPECT_EQ(event_driven::check(st).rfind("contact:", 0), 0u) << event_driven::check(st);
  st = {};
  st.stiffness = 1e4;  // a stiffness without a compliant contact
  EXPECT_EQ(event_driven::check(st).rfind("stiffness:", 0), 0u) << event_driven::check(st);
  st = kelvin_voigt(-1.0);
  EXPECT_EQ(event_driven::check(st).rfind("stiffness:", 0), 0u) << event_driven::check(st);
  st = kelvin_voigt(1e4);
  st.variant = "lemke";
  EXPECT_EQ(event_driven::check(st).rfind("variant:", 0), 0u) << event_driven::check(st);
  EXPECT_EQ(event_driven::check(kelvin_voigt(1e4)), "");
  st = {};
  st.contact = "rigid";
  EXPECT_EQ(event_driven::check(st), "");
}

}  // namespace kelvin_voigt_reference_tests
}  // namespace pb
