// The compliant solver's Newmark integrator (solvers/compliant/newmark.cpp) converges at its
// order, 2, with contact elements and yielding bodies: each step is split where a contact
// begins or ends and where a body yields, so that within each part the force law is smooth.
//
// What is measured: the error of body 0's state (u0 and v0) on a fixed time grid, the steps of
// the coarsest N (every finer N lands on them), against the exact Kelvin-Voigt solution (the
// event-driven reference with contact = kelvin-voigt) or, for yielding bodies, CVODE at rtol
// 1e-12 on the same model. Not Pi1: a fixed-step run's Pi1 is the largest |u0| over its steps'
// ends (cases/README.md), a sampled maximum whose error moves with where the peak falls
// between two step ends, not smoothly with h. The order is the least-squares slope of
// log(error) over log(N), never one pair's ratio.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cases/case.hpp"
#include "cases/system.hpp"
#include "solvers/compliant/compliant.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "solvers/event_driven/kelvin_voigt.hpp"
#include "kit/testing.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace newmark_order_tests {

// K = 1e3: the contact's own frequency w_c is ~32 w0 (wall) to ~45 w0 (pair, m_eff = m / 2), so
// w_c h = 0.19 to 0.27 at N = 512 and 0.012 to 0.017 at N = 8192: the range where the error
// is h^2 times a constant. Below it the error is in the trapezoidal rule's phase error at w_c,
// a smooth function of w_c h but not yet h^2 (measured slopes 0.9 to 1.9 from N = 64 to 512).
constexpr double kStiffness = 1e3;
const std::vector<int> kSteps = {512, 1024, 2048, 4096, 8192};

// The reference's state on the grid t_s = s h_coarse, s = 0..M (M h_coarse <= t_end): its
// history sampled at M + 1 equally spaced times of a run to M h_coarse.
Result reference_on_grid(const System& s, bool yields, double h_coarse) {
  System to = s;
  const long m = static_cast<long>(std::floor(s.t_end / h_coarse * (1.0 + 1e-12)));
  to.t_end = static_cast<double>(m) * h_coarse;
  Settings st;
  st.stiffness = kStiffness;
  st.history_samples = static_cast<int>(m + 1);
  if (yields) {  // no exact reference for a yielding body with elements: CVODE tight
    st.rtol = 1e-12;
    return compliant::solve(to, st);
  }
  st.contact = event_driven::kKelvinVoigtContact;
  return event_driven::solve(to, st);
}

Result newmark(const System& s, int n) {
  Settings st;
  st.stiffness = kStiffness;
  st.integrator = "newmark";
  st.steps = n;
  st.history_samples = 1;  // every step
  return compliant::solve(s, st);
}

// The largest error of u0 (over a_p / w_p^2) and of v0 (over a_p / w_p) on the reference's
// grid: Newmark's step k = s N / N_coarse is the grid's point s.
double state_error(const System& s, const Result& ref, const Result& nm, int stride) {
  const History& a = ref.history;
  const History& b = nm.history;
  const auto w = static_cast<std::size_t>(a.row_size());
  const auto u0 = 1 + static_cast<std::size_t>(s.ref), v0 = u0 + static_cast<std::size_t>(s.n_bodies());
  const double lu = s.length_scale(), lv = s.a_p / s.pulse.w;
  double worst = 0.0;
  for (std::size_t r = 0; r < a.rows(); ++r) {
    const std::size_t k = r * static_cast<std::size_t>(stride);
    if (k >= b.rows()) break;
    worst = std::max(worst, std::abs(a.data[r * w + u0] - b.data[k * w + u0]) / lu);
    worst = std::max(worst, std::abs(a.data[r * w + v0] - b.data[k * w + v0]) / lv);
  }
  return worst;
}

// -slope of the least-squares line through (log N, log error).
double observed_order(const std::vector<int>& ns, const std::vector<double>& errors) {
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  const double m = static_cast<double>(ns.size());
  for (std::size_t i = 0; i < ns.size(); ++i) {
    const double x = std::log(static_cast<double>(ns[i])), y = std::log(errors[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return -(m * sxy - sx * sy) / (m * sxx - sx * sx);
}

struct OrderCase {
  std::string label;
  Case c;
  bool yields;
};

std::vector<OrderCase> order_cases() {
  std::vector<OrderCase> out;
  for (PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
    const std::string pulse = p == PulseShape::sine ? "sine" : "cosine";
    out.push_back({"wall " + pulse, test::make_case(Scene::wall, p, 0.5, 1.0, 0.5), false});
    out.push_back({"pair " + pulse, test::make_case(Scene::pair, p, 1.0, 0.5, 0.5), false});
    out.push_back({"yielding pair " + pulse, test::yielding_case(Scene::pair, p, 1.0, 0.5, 0.5, 0.5, 0.05), true});
  }
  return out;
}

TEST(NewmarkOrder, StateErrorFallsAtSecondOrderWithContactsAndYield) {
  for (const OrderCase& oc : order_cases()) {
    const System s = make_system(oc.c);
    const Result ref = reference_on_grid(s, oc.yields, s.step(kSteps.front()));
    ASSERT_EQ(ref.status, Status::ok) << oc.label << ": " << ref.message;
    std::vector<double> errors;
    long impacts = 0;
    for (int n : kSteps) {
      const Result r = newmark(s, n);
      ASSERT_EQ(r.status, Status::ok) << oc.label << " N " << n << ": " << r.message;
      impacts = r.impacts;
      errors.push_back(state_error(s, ref, r, n / kSteps.front()));
      RecordProperty(oc.label + " N" + std::to_string(n), test::sci(errors.back()));
    }
    EXPECT_GT(impacts, 0) << oc.label << ": no contact closed, the case tests nothing";
    const double order = observed_order(kSteps, errors);
    RecordProperty(oc.label + " order", test::sci(order));
    EXPECT_NEAR(order, 2.0, 0.3) << oc.label;
    // And error N^2 within a factor 1.5 over the range: no pair of N may step out of line.
    std::vector<double> scaled;
    for (std::size_t i = 0; i < kSteps.size(); ++i) scaled.push_back(errors[i] * kSteps[i] * kSteps[i]);
    const auto [low, high] = std::minmax_element(scaled.begin(), scaled.end());
    RecordProperty(oc.label + " error N^2 spread", test::sci(*high / *low));
    EXPECT_LT(*high / *low, 1.5) << oc.label;
  }
}

}  // namespace newmark_order_tests
}  // namespace pb
