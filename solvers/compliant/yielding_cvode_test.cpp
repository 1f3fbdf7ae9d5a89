// The compliant solver's cvode integrator with yielding bodies (solvers/compliant/cvode_run.cpp:
// each body's branch a mode, switched at CVODE's roots on yield and unloading): where no
// contact closes its model is the reference's, and it converges to it; with contacts it meets
// Newmark's bilinear law on the same element; a yield no motion reaches gives its elastic run.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cases/case.hpp"
#include "cases/system.hpp"
#include "solvers/compliant/compliant.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "kit/testing.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace yielding_cvode_tests {

Result cvode_at(const System& s, double rtol) {
  Settings set;
  set.rtol = rtol;
  return compliant::solve(s, set);
}

// The single-body and pair cases of a yielding family, Pi_y0 from strongly yielding to barely
// (the elastic Pi1 of these cases is 1 to 3), every alpha, both pulses.
std::vector<Case> family(double pi3) {
  std::vector<Case> out;
  for (Scene scene : {Scene::wall, Scene::pair})
    for (double pi_y : {0.1, 0.5, 2.0})
      for (double alpha : {0.0, 0.05, 0.2})
        for (PulseShape pulse : {PulseShape::sine, PulseShape::cosine}) {
          Case c = test::yielding_case(scene, pulse, 1.0, 0.5, 0.5, pi_y, alpha);
          c.pi3 = pi3;
          out.push_back(c);
        }
  return out;
}

struct Errors {
  double pi1 = 0.0, residual = 0.0, hysteretic = 0.0;
  void add(const Result& r, const Result& ref) {
    pi1 = std::max(pi1, std::abs(r.pi1 - ref.pi1) / ref.pi1);
    residual = std::max(residual, std::abs(r.residual - ref.residual));  // a Pi term: ~1
    hysteretic = std::max(hysteretic, std::abs(r.hysteretic - ref.hysteretic));  // a share of the input
  }
};

Errors against_reference(double rtol) {
  Errors e;
  for (const Case& c : family(1000.0)) {
    const System s = make_system(c);
    const Result ref = event_driven::solve(s, Settings{});
    const Result r = cvode_at(s, rtol);
    EXPECT_EQ(ref.status, Status::ok) << ref.message;
    EXPECT_EQ(r.status, Status::ok) << r.message;
    EXPECT_EQ(r.impacts, 0);
    e.add(r, ref);
  }
  return e;
}

// No contact closes (Pi3 = 1000): the compliant model is the reference's, so CVODE converges
// to the exact answer as its tolerance falls. At rtol 1e-12 every Pi1, residual and
// hysteretic share is within 1e-8 (measured worst 6.3e-11, 2.5e-10, 1.4e-10), and the
// Pi1 error falls at least 100 times from rtol 1e-8, the default (measured 8.9e-8).
TEST(YieldingCvode, ConvergesToTheReferenceWhereNoContactCloses) {
  const Errors loose = against_reference(1e-8), tight = against_reference(1e-12);
  RecordProperty("pi1_error_rtol_1e-8", test::sci(loose.pi1));
  RecordProperty("pi1_error_rtol_1e-12", test::sci(tight.pi1));
  RecordProperty("residual_error_rtol_1e-12", test::sci(tight.residual));
  RecordProperty("hysteretic_error_rtol_1e-12", test::sci(tight.hysteretic));
  EXPECT_LT(tight.pi1, 1e-8);
  EXPECT_LT(tight.residual, 1e-8);
  EXPECT_LT(tight.hysteretic, 1e-8);
  EXPECT_LT(tight.pi1, loose.pi1 / 100.0);
}

// With contacts (Pi3 = 0.5, Kelvin-Voigt at K = 1e3, which Newmark's step resolves), Newmark's
// return map converges to CVODE's roots on the same model at second order: its largest errors
// over the family fall at least 1000 times from N = 1024 to 65536 (second order: 4096). Before
// Newmark split its steps where a contact begins and ends, a contact inside a step made it first
// order there, and erratic in N (Pi1 1.4e-2 at N = 1024, 1.6e-4 at 65536: 89 times closer, the
// residual 89 and the hysteretic share 107 times); now Pi1 1.6e-3 and 4.0e-7 (3960 times), the
// residual 3900 and the hysteretic share 3930 times. CVODE's own answer moves by at most 5e-9
// from rtol 1e-10 to 1e-12 on these cases.
TEST(YieldingCvode, NewmarkConvergesToItWithContacts) {
  const std::vector<int> ns = {1024, 65536};
  std::vector<Errors> by_n(ns.size());
  for (const Case& c : family(0.5)) {
    const System s = make_system(c);
    Settings set;
    set.stiffness = 1e3;
    set.rtol = 1e-12;
    const Result r = compliant::solve(s, set);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    set.rtol = 0.0;
    set.integrator = "newmark";
    for (std::size_t k = 0; k < by_n.size(); ++k) {
      set.steps = ns[k];
      const Result nm = compliant::solve(s, set);
      ASSERT_EQ(nm.status, Status::ok) << nm.message;
      by_n[k].add(nm, r);
    }
  }
  for (std::size_t k = 0; k < by_n.size(); ++k) {
    const std::string n = std::to_string(ns[k]);
    RecordProperty("newmark_pi1_error_N" + n, test::sci(by_n[k].pi1));
    RecordProperty("newmark_residual_error_N" + n, test::sci(by_n[k].residual));
    RecordProperty("newmark_hysteretic_error_N" + n, test::sci(by_n[k].hysteretic));
  }
  EXPECT_LT(by_n[1].pi1, by_n[0].pi1 / 1000.0);
  EXPECT_LT(by_n[1].residual, by_n[0].residual / 1000.0);
  EXPECT_LT(by_n[1].hysteretic, by_n[0].hysteretic / 1000.0);
}

// Pi_y 1e6 (no motion reaches it): the elastic run's answer with contacts, to CVODE's
// tolerance (the yielding run carries the ground's work as one more state, so its steps are
// not the elastic run's bit for bit; measured within 9.1e-11 at rtol 1e-12), and no dissipation.
TEST(YieldingCvode, AFarYieldGivesTheElasticRun) {
  double worst = 0.0;
  for (Scene scene : {Scene::wall, Scene::pair, Scene::row3})
    for (PulseShape pulse : {PulseShape::sine, PulseShape::cosine}) {
      const Case elastic = test::make_case(scene, pulse, 1.0, 0.5, 0.5);
      const Case far = test::yielding_case(scene, pulse, 1.0, 0.5, 0.5, 1e6, 0.05);
      const Result e = cvode_at(make_system(elastic), 1e-12), y = cvode_at(make_system(far), 1e-12);
      ASSERT_EQ(e.status, Status::ok) << e.message;
      ASSERT_EQ(y.status, Status::ok) << y.message;
      EXPECT_NEAR(y.pi1, e.pi1, 1e-9 * e.pi1);
      worst = std::max(worst, std::abs(y.pi1 - e.pi1) / e.pi1);
      EXPECT_EQ(y.impacts, e.impacts);
      EXPECT_EQ(y.hysteretic, 0.0);
      EXPECT_EQ(y.residual, 0.0);
      EXPECT_TRUE(std::isnan(e.residual));
    }
  RecordProperty("pi1_difference", test::sci(worst));
}

}  // namespace yielding_cvode_tests
}  // namespace pb
