// The paper's findings (Dimitrakopoulos, Makris & Kappos 2009), checked on the reference's
// spectra of the paper case set (cases/sets/paper.toml, eps = 0.5). Where the reference
// disagrees with the paper, the test asserts what the reference does and says so; the
// report (reports/paper/) shows the same numbers. Contact amplifies (deamplifies) a
// response when Pi1 is above (below) the no-contact Pi1 by more than kEffect; within it,
// contact has no effect. kEffect and kNear are the report's NO_EFFECT and NEAR
// (reports/paper/analysis.py).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "cases/case_set.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"
#include "sweep/sweep.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace paper_claims_tests {

constexpr double kEffect = 0.02;
constexpr double kNear = 1.25;  // a Pi2 within this factor of another is near it

const CaseSet& paper_set() {
  static const CaseSet set = load_case_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/paper.toml");
  return set;
}

std::vector<Row> solve(const std::vector<Case>& cases) {
  return run_sweep(cases, *find_solver("event-driven"), Settings{});
}

std::vector<Row> family(const std::string& name) {
  std::vector<Case> cases;
  for (const Case& c : paper_set().cases)
    if (c.family == name) cases.push_back(c);
  EXPECT_FALSE(cases.empty()) << name;
  return solve(cases);
}

// A spectrum: the rows of one curve, in increasing Pi2.
using Curve = std::vector<Row>;
using CurveKey = std::tuple<PulseShape, Directivity, double, double>;  // pulse, directivity, Pi5, Pi6

std::map<CurveKey, Curve> spectra(const std::vector<Row>& rows) {
  std::map<CurveKey, Curve> out;
  for (const Row& r : rows) out[{r.input.pulse, r.input.directivity, r.input.pi5, r.input.pi6}].push_back(r);
  for (auto& [key, curve] : out)
    std::sort(curve.begin(), curve.end(), [](const Row& a, const Row& b) { return a.input.pi2 < b.input.pi2; });
  return out;
}

std::string label(const CurveKey& k) {
  return std::string(name(std::get<0>(k))) + " " + std::string(name(std::get<1>(k))) +
         " Pi5=" + std::to_string(std::get<2>(k)) + " Pi6=" + std::to_string(std::get<3>(k));
}

double ratio(const Row& r) { return r.result.pi1 / r.pi1_no_contact; }

// The extreme of Pi1 / Pi1_no_contact over lo <= Pi2 <= hi.
double max_ratio(const Curve& c, double lo, double hi) {
  double m = 0.0;
  for (const Row& r : c)
    if (r.input.pi2 >= lo && r.input.pi2 <= hi) m = std::max(m, ratio(r));
  return m;
}
double min_ratio(const Curve& c, double lo, double hi) {
  double m = INFINITY;
  for (const Row& r : c)
    if (r.input.pi2 >= lo && r.input.pi2 <= hi) m = std::min(m, ratio(r));
  return m;
}

// Section "DIMENSIONAL ANALYSIS", Fig. 3: spectra for several pulse amplitudes at one Pi3
// are one curve in Pi terms. On the asymmetric row3 of the fig3 family, the three a_p
// give the same Pi1 to round-off at every Pi2.
TEST(PaperClaims, Fig3SpectraOfDifferentAmplitudesCollapseOnRow3) {
  std::map<double, std::vector<double>> by_pi2;
  for (const Row& r : family("fig3")) by_pi2[r.input.pi2].push_back(r.result.pi1);
  ASSERT_EQ(by_pi2.size(), 200u);
  double worst = 0.0;
  for (const auto& [pi2, pi1] : by_pi2) {
    ASSERT_EQ(pi1.size(), 3u);
    const auto [lo, hi] = std::minmax_element(pi1.begin(), pi1.end());
    worst = std::max(worst, (*hi - *lo) / *hi);
  }
  // Measured 1.1e-15: the scaling's round-off (event times are found to an ulp).
  EXPECT_LE(worst, 1e-12);
  ::testing::Test::RecordProperty("fig3_spread", std::to_string(worst));
}

// Section "RESPONSE SPECTRA" (Pi6 = 1): as Pi5 tends to 1 the neighbours move more and more
// alike and the response tends to the no-contact one. At Pi5 = 1 exactly the gap never
// changes: not a single impact, Pi1 equal to the no-contact Pi1.
TEST(PaperClaims, AsPi5TendsToOneTheResponseTendsToTheNoContactOne) {
  for (PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
    std::vector<double> deviation;  // max over Pi2 of |Pi1 / Pi1_nc - 1|, per Pi5
    const std::vector<double> pi5s = {0.5, 0.75, 0.9, 0.99, 1.0, 1.01, 1.1, 1.33, 2.0};
    for (double pi5 : pi5s) {
      std::vector<Case> cases;
      for (int i = 0; i < 60; ++i) {
        Case c;
        c.scene = Scene::pair;
        c.pulse = p;
        c.pi2 = 0.1 * std::pow(100.0, i / 59.0);
        c.pi5 = pi5;
        cases.push_back(c);  // Pi3 = 0.5, eps = 0.5, Pi6 = 1, normal: the Fig. 4 defaults
      }
      double d = 0.0;
      long impacts = 0;
      for (const Row& r : solve(cases)) {
        d = std::max(d, std::abs(ratio(r) - 1.0));
        impacts += r.result.impacts;
      }
      if (pi5 == 1.0) {
        EXPECT_EQ(impacts, 0) << name(p);
        EXPECT_EQ(d, 0.0) << name(p);
      }
      deviation.push_back(d);
    }
    // Falls towards Pi5 = 1 from either side, strictly until it vanishes.
    for (std::size_t i = 0; i + 1 < deviation.size(); ++i) {
      const std::size_t nearer = i < 4 ? i + 1 : i, farther = i < 4 ? i : i + 1;
      if (deviation[nearer] > 0.0) {
        EXPECT_LT(deviation[nearer], deviation[farther]) << name(p) << " Pi5=" << pi5s[nearer];
      }
    }
    // With the gap of Pi3 = 0.5 it vanishes before Pi5 = 1: within 1 % of it the bodies never
    // touch (measured: none from 0.99 to 1.01, none to 1.1 under the sine pulse; 8.7 % and
    // 1.0 % left at Pi5 = 0.9).
    EXPECT_EQ(deviation[3], 0.0) << name(p);
    EXPECT_EQ(deviation[5], 0.0) << name(p);
    EXPECT_GT(deviation[2], 0.0) << name(p);
    for (std::size_t i = 0; i < pi5s.size(); ++i)
      ::testing::Test::RecordProperty(std::string(name(p)) + "_pi5_" + std::to_string(pi5s[i]),
                                      std::to_string(deviation[i]));
  }
}

// Section "RESPONSE SPECTRA": the flexible body's spectrum peaks where the stiffer
// neighbour resonates, Pi2 = Pi5. The reference agrees under the cosine pulse for
// Pi5 = 0.25, 0.5, 0.75 (a local maximum within kNear of Pi5) and disagrees under the sine
// pulse, whose flexible-body spectra have no local maximum near Pi5 at all.
TEST(PaperClaims, FlexibleBodyPeaksAtTheStifferNeighboursResonanceUnderTheCosinePulseOnly) {
  for (const auto& [key, curve] : spectra(family("fig4-flexible"))) {
    const double pi5 = std::get<2>(key);
    bool near = false;
    for (std::size_t i = 1; i + 1 < curve.size(); ++i) {
      const double y = curve[i].result.pi1;
      const bool local_max = y > curve[i - 1].result.pi1 && y >= curve[i + 1].result.pi1;
      if (local_max && std::abs(std::log(curve[i].input.pi2 / pi5)) < std::log(kNear)) near = true;
    }
    if (std::get<0>(key) == PulseShape::cosine && pi5 >= 0.25) {
      EXPECT_TRUE(near) << label(key);
    } else if (std::get<0>(key) == PulseShape::sine) {
      EXPECT_FALSE(near) << label(key) << ": the reference now agrees with the paper; update the report";
    }
  }
}

// Section "RESPONSE SPECTRA": three regions. A flexible body (Pi5 < 1) is amplified at low
// Pi2, deamplified around Pi2 ~ 1, and untouched (no contact) at high Pi2. A stiff body is
// untouched at low Pi2 and amplified at high Pi2, as the paper says; the deamplification
// near Pi2 ~ 1 appears under the cosine pulse only: under the sine pulse the stiff body's
// response is within kEffect of the no-contact one up to where the amplification starts.
TEST(PaperClaims, ThreeSpectralRegionsSwapBetweenFlexibleAndStiffBodies) {
  for (const auto& [key, c] : spectra(family("fig4-flexible"))) {
    EXPECT_GT(max_ratio(c, 0.1, 0.7), 1 + kEffect) << label(key);  // amplified
    EXPECT_LT(min_ratio(c, 0.8, 1.4), 1 - kEffect) << label(key);  // deamplified around 1
    EXPECT_EQ(min_ratio(c, 2.0, 10.0), 1.0) << label(key);  // no contact at all
    EXPECT_EQ(max_ratio(c, 2.0, 10.0), 1.0) << label(key);
  }
  for (const auto& [key, c] : spectra(family("fig4-stiff"))) {
    const double pi5 = std::get<2>(key);
    EXPECT_LT(max_ratio(c, 0.1, 0.75), 1 + kEffect) << label(key);  // no effect at low Pi2
    EXPECT_GT(min_ratio(c, 0.1, 0.75), 1 - kEffect) << label(key);
    EXPECT_GT(max_ratio(c, 1.5, 10.0), 1 + kEffect) << label(key);  // amplified at high Pi2
    if (std::get<0>(key) == PulseShape::cosine) {
      EXPECT_LT(min_ratio(c, 0.8, 1.4), 1 - kEffect) << label(key);  // measured 0.79-0.86
    } else {
      // Up to 0.9 Pi5^(1/3) (0.99 at Pi5 = 1.33, 1.9 at Pi5 = 10): no deamplification.
      EXPECT_GT(min_ratio(c, 0.8, 0.9 * std::cbrt(pi5)), 1 - kEffect) << label(key);
    }
  }
}

// Section "COMPARISON OF ONE-SIDED AND TWO-SIDED POUNDING": a flexible body between two
// identical neighbours (symmetric row3, Fig. 7) reaches a smaller peak than against one
// (pair, Fig. 4), under both pulses and for every flexible Pi5; its largest amplification
// over the no-contact response is smaller too (measured 1.0-1.6 against 1.2-5.2), except at
// Pi5 = 0.75 under the cosine pulse, where both are 1.24.
TEST(PaperClaims, TwoSidedPoundingAmplifiesAFlexibleBodyLessThanOneSided) {
  const auto one = spectra(family("fig4-flexible"));
  std::map<CurveKey, Curve> two;
  for (const auto& [key, curve] : spectra(family("fig7")))
    if (std::get<2>(key) < 1.0) two[key] = curve;
  ASSERT_EQ(one.size(), two.size());
  for (const auto& [key, c1] : one) {
    const Curve& c2 = two.at(key);
    auto peak = [](const Curve& c) {
      double m = 0.0;
      for (const Row& r : c) m = std::max(m, r.result.pi1);
      return m;
    };
    EXPECT_LT(peak(c2), peak(c1)) << label(key);
    const double a1 = max_ratio(c1, 0.1, 10.0), a2 = max_ratio(c2, 0.1, 10.0);
    if (std::get<2>(key) <= 0.5) {
      EXPECT_LT(a2, a1) << label(key);
    } else {
      EXPECT_LE(a2, a1 * 1.01) << label(key);
    }
  }
}

// Section "INCOMPLETE SIMILARITY", Fig. 10: on the ln Pi1 - ln Pi6 plane at fixed Pi2, the
// curves fall into straight branches: flat where there is no contact (exactly: body 0 does
// not feel m1 then), a negative slope on the main branch, and a positive slope on the
// counter-intuitive one. A branch is a maximal run of consecutive Pi6 points with contact
// whose local slopes share a sign (|slope| > 0.02); fitted by least squares when it holds
// 8 points or more (a fifth of the Pi6 decades).
TEST(PaperClaims, Fig10BranchesAreFlatWithoutContactAndOfBothSignsWithIt) {
  struct Fit {
    double slope, r2;
  };
  auto fit = [](const std::vector<double>& x, const std::vector<double>& y) {
    const double n = static_cast<double>(x.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i], syy += y[i] * y[i];
    }
    const double b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    const double r = (n * sxy - sx * sy) / std::sqrt((n * sxx - sx * sx) * (n * syy - sy * sy));
    return Fit{b, r * r};
  };
  std::map<std::tuple<PulseShape, double, double>, std::vector<Row>> curves;  // pulse, Pi5, Pi2
  for (const Row& r : family("fig10")) curves[{r.input.pulse, r.input.pi5, r.input.pi2}].push_back(r);
  int flat = 0;
  std::vector<Fit> negative, positive;
  for (auto& [key, c] : curves) {
    std::sort(c.begin(), c.end(), [](const Row& a, const Row& b) { return a.input.pi6 < b.input.pi6; });
    ASSERT_EQ(c.size(), 41u);
    bool any_contact = false;
    for (const Row& r : c) any_contact = any_contact || r.result.impacts > 0;
    if (!any_contact) {
      ++flat;
      for (const Row& r : c) EXPECT_EQ(r.result.pi1, c.front().result.pi1);
      continue;
    }
    std::vector<double> x = {std::log(c[0].input.pi6)}, y = {std::log(c[0].result.pi1)};
    int sign = 0;
    auto close = [&] {
      if (x.size() >= 8 && sign != 0) (sign < 0 ? negative : positive).push_back(fit(x, y));
    };
    for (std::size_t i = 1; i < c.size(); ++i) {
      const double xi = std::log(c[i].input.pi6), yi = std::log(c[i].result.pi1);
      const double s = (yi - y.back()) / (xi - x.back());
      const int si = s > 0.02 ? 1 : s < -0.02 ? -1 : 0;
      if (si != sign || c[i].result.impacts == 0) {
        close();
        x = {x.back()}, y = {y.back()};
        sign = si;
      }
      x.push_back(xi), y.push_back(yi);
    }
    close();
  }
  EXPECT_GE(flat, 5);  // Pi2 = 4 (and 2 for Pi5 = 0.75): no contact at any mass ratio
  ASSERT_FALSE(negative.empty());
  ASSERT_FALSE(positive.empty());
  for (const Fit& f : negative) {
    EXPECT_LT(f.slope, -0.02);
  }
  for (const Fit& f : positive) {
    EXPECT_GT(f.slope, 0.02);
  }
  // The branches are nearly straight: the best of each sign (measured R^2 > 0.99).
  auto best_r2 = [](const std::vector<Fit>& fits) {
    double m = 0.0;
    for (const Fit& f : fits) m = std::max(m, f.r2);
    return m;
  };
  EXPECT_GT(best_r2(negative), 0.98);
  EXPECT_GT(best_r2(positive), 0.98);
  ::testing::Test::RecordProperty("negative_branches", std::to_string(negative.size()));
  ::testing::Test::RecordProperty("positive_branches", std::to_string(positive.size()));
}

}  // namespace paper_claims_tests
}  // namespace pb
