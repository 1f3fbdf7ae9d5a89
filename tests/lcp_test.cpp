// LCP solvers (kit/lcp/): enumeration as ground truth, Lemke (plain and with a
// lexicographic right-hand side), PGS (run-time and fixed size), and the closed forms of
// small.hpp, on seeded random problems of sizes 1..10.
//
// Every check is relative to the problem's size s = ||A||_inf ||z||_inf + ||q||_inf:
//   min(w) >= -tol s,  max_i |z_i w_i| <= tol s ||z||_inf,  min(z) >= -tol ||z||_inf,
// with z compared to the planted solution (P-matrices have exactly one) to a stated tol.

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "kit/lcp/enumerate.hpp"
#include "kit/lcp/lemke.hpp"
#include "kit/lcp/pgs.hpp"
#include "kit/lcp/small.hpp"

namespace pb::lcp {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace lcp_tests {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr int kMaxSize = 10;
// Problems per size and family. Unoptimised (Debug, sanitizer) builds look for memory
// and undefined-behaviour errors, not for rare numerical cases, and run ~20x slower.
#ifdef NDEBUG
constexpr int kPerSize = 300;
#else
constexpr int kPerSize = 100;
#endif

struct Problem {
  MatrixXd a;
  VectorXd q;
  VectorXd z;  // a planted solution (the solution when A is a P-matrix)
};

class Gen {
 public:
  explicit Gen(unsigned long seed) : rng_(seed) {}

  double normal() { return normal_(rng_); }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }

  MatrixXd normal(Index rows, Index cols) {
    MatrixXd m(rows, cols);
    for (Index j = 0; j < cols; ++j)
      for (Index i = 0; i < rows; ++i) m(i, j) = normal();
    return m;
  }

  // Strictly diagonally dominant with a positive diagonal, not symmetric: a P-matrix.
  MatrixXd diagonally_dominant(Index n) {
    MatrixXd a(n, n);
    for (Index i = 0; i < n; ++i) {
      double off = 0.0;
      for (Index j = 0; j < n; ++j) {
        if (i == j) continue;
        a(i, j) = uniform(-1.0, 1.0);
        off += std::abs(a(i, j));
      }
      a(i, i) = off + uniform(0.1, 1.0);
    }
    return a;
  }

  // B B^T + I: symmetric positive definite, a P-matrix.
  MatrixXd spd(Index n) {
    const MatrixXd b = normal(n, n) / std::sqrt(static_cast<double>(n));
    return b * b.transpose() + MatrixXd::Identity(n, n);
  }

  // B B^T with B of n / 2 columns: positive semi-definite of rank n / 2 (0 for n = 1).
  MatrixXd rank_deficient(Index n) {
    const MatrixXd b = normal(n, n / 2);
    return b * b.transpose();
  }

  // Q diag(1 ... 1e-10) Q^T with Q random orthogonal: SPD of condition 1e10.
  MatrixXd near_singular(Index n) {
    const MatrixXd q = normal(n, n).householderQr().householderQ();
    VectorXd lambda(n);
    for (Index i = 0; i < n; ++i)
      lambda(i) = n == 1 ? 1.0 : std::pow(10.0, -10.0 * static_cast<double>(i) / static_cast<double>(n - 1));
    const MatrixXd a = q * lambda.asDiagonal() * q.transpose();
    return 0.5 * (a + a.transpose());
  }

  // q = w* - A z* for complementary z*, w* >= 0; with degenerate_share > 0 some
  // components have z*_i = w*_i = 0. Values are kept away from 0 otherwise.
  Problem planted(MatrixXd a, double degenerate_share) {
    const Index n = a.rows();
    VectorXd z = VectorXd::Zero(n), w = VectorXd::Zero(n);
    for (Index i = 0; i < n; ++i) {
      const double u = uniform(0.0, 1.0);
      if (u < degenerate_share) continue;
      if (u < degenerate_share + 0.5 * (1.0 - degenerate_share))
        z(i) = uniform(0.1, 2.0);
      else
        w(i) = uniform(0.1, 2.0);
    }
    VectorXd q = w - a * z;
    return {std::move(a), std::move(q), std::move(z)};
  }

 private:
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_;
};

double inf_norm(const MatrixXd& m) { return m.size() ? m.cwiseAbs().rowwise().sum().maxCoeff() : 0.0; }
double max_abs(const VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

// How well z solves LCP(A, q), each number relative as in the file comment (<= 0 is exact).
struct Fit {
  double z_neg = 0.0;  // -min(z) / ||z||
  double w_neg = 0.0;  // -min(w) / s
  double comp = 0.0;   // max |z_i w_i| / (s ||z||)
  double worst() const { return std::max({z_neg, w_neg, comp}); }
};

Fit fit(const MatrixXd& a, const VectorXd& q, const VectorXd& z) {
  Fit f;
  if (q.size() == 0) return f;
  const VectorXd w = a * z + q;
  const double zn = max_abs(z);
  const double s = inf_norm(a) * zn + max_abs(q);
  if (zn > 0.0) f.z_neg = -z.minCoeff() / zn;
  if (s > 0.0) f.w_neg = -w.minCoeff() / s;
  if (s > 0.0 && zn > 0.0) f.comp = z.cwiseProduct(w).cwiseAbs().maxCoeff() / (s * zn);
  return f;
}

double rel_diff(const VectorXd& x, const VectorXd& ref) { return max_abs(x - ref) / std::max(1.0, max_abs(ref)); }

// The measured worst cases go to the test report (--gtest_output=xml), where the margins
// of the tolerances below can be re-checked.
void record(const std::string& key, double value) {
  std::ostringstream os;
  os << value;
  ::testing::Test::RecordProperty(key, os.str());
}

enum class Family { dominant, spd, rank_deficient, near_singular };

MatrixXd matrix_of(Gen& g, Family f, Index n) {
  switch (f) {
    case Family::dominant: return g.diagonally_dominant(n);
    case Family::spd: return g.spd(n);
    case Family::rank_deficient: return g.rank_deficient(n);
    case Family::near_singular: return g.near_singular(n);
  }
  return {};
}

// Runs Lemke and enumeration on kPerSize planted problems of each size 1..kMaxSize and
// returns the worst fits and differences seen.
struct Worst {
  double lemke_fit = 0.0, enum_fit = 0.0;
  double lemke_vs_planted = 0.0, enum_vs_planted = 0.0, lemke_vs_enum = 0.0;
  int not_solved = 0;
  int max_pivots = 0;
};

Worst run_family(Family family, double degenerate_share, unsigned long seed, const EnumerateSettings& es = {}) {
  Gen g(seed);
  Worst worst;
  LemkeWorkspace ws;
  for (Index n = 1; n <= kMaxSize; ++n) {
    VectorXd z(n);
    for (int t = 0; t < kPerSize; ++t) {
      const Problem p = g.planted(matrix_of(g, family, n), degenerate_share);
      const LemkeResult lr = lemke(p.a, p.q, z, ws);
      const EnumerateResult er = enumerate(p.a, p.q, es);
      if (lr.status != Status::solved || er.status != Status::solved) {
        ++worst.not_solved;
        continue;
      }
      worst.max_pivots = std::max(worst.max_pivots, lr.pivots);
      worst.lemke_fit = std::max(worst.lemke_fit, fit(p.a, p.q, z).worst());
      worst.enum_fit = std::max(worst.enum_fit, fit(p.a, p.q, er.z).worst());
      worst.lemke_vs_planted = std::max(worst.lemke_vs_planted, rel_diff(z, p.z));
      worst.enum_vs_planted = std::max(worst.enum_vs_planted, rel_diff(er.z, p.z));
      worst.lemke_vs_enum = std::max(worst.lemke_vs_enum, rel_diff(z, er.z));
    }
  }
  const std::string tag = std::to_string(static_cast<int>(family)) + "_" + std::to_string(degenerate_share) + "_";
  record(tag + "lemke_fit", worst.lemke_fit);
  record(tag + "enum_fit", worst.enum_fit);
  record(tag + "lemke_vs_planted", worst.lemke_vs_planted);
  record(tag + "enum_vs_planted", worst.enum_vs_planted);
  record(tag + "lemke_vs_enum", worst.lemke_vs_enum);
  record(tag + "max_pivots", worst.max_pivots);
  return worst;
}

// Fits are rounding-level: measured <= 3e-16 on the well-conditioned families and
// <= 9e-16 at condition 1e10 (over 5 seeds); 1e-13 leaves a factor 100.
constexpr double kFitTol = 1e-13;
// Rank-deficient PSD problems: the best-fitting active set of enumeration itself fits
// only to 5e-14 (its principal blocks are ill-conditioned), and Lemke matches it.
constexpr double kFitTolRankDeficient = 1e-12;
// Solutions of the well-conditioned P-matrix families (condition <= ~1e2) agree to
// measured <= 9e-16 relative; 1e-13 leaves a factor 100.
constexpr double kAgreeTol = 1e-13;
// At condition 1e10 z is determined only to cond * eps ~ 1e-6 (measured 1.1e-6).
constexpr double kAgreeTolNearSingular = 1e-4;

// A family of planted problems and what Lemke and enumeration must reach on it.
struct FamilyCase {
  const char* name;
  Family family;
  double degenerate_share;  // of the components with z*_i = w*_i = 0: the ratio tests tie
  unsigned long seed;
  double fit_tol;
  // The solutions' agreement with each other and with the planted one; 0: not compared,
  // where solutions need not be unique.
  double agree_tol;
};

class LcpLemkeFamily : public ::testing::TestWithParam<FamilyCase> {};

TEST_P(LcpLemkeFamily, SolvesPlantedProblemsWithinTheFamilysFitAndAgreementTolerances) {
  const FamilyCase& c = GetParam();
  const Worst w = run_family(c.family, c.degenerate_share, c.seed);
  EXPECT_EQ(w.not_solved, 0);
  EXPECT_LE(w.lemke_fit, c.fit_tol);
  EXPECT_LE(w.enum_fit, c.fit_tol);
  if (c.agree_tol == 0.0) return;
  EXPECT_LE(w.lemke_vs_planted, c.agree_tol);
  EXPECT_LE(w.enum_vs_planted, c.agree_tol);
  EXPECT_LE(w.lemke_vs_enum, c.agree_tol);
}

// Near-singular: condition 1e10, with and without degenerate components; the fit (a
// backward error) stays at rounding level, z itself is determined only to about cond * eps.
// (Without LemkeSettings::polish the fit there was up to 4e-8 and z off by O(1).)
INSTANTIATE_TEST_SUITE_P(
    LcpLemke, LcpLemkeFamily,
    ::testing::Values(
        FamilyCase{"DiagonallyDominant", Family::dominant, 0.0, 1, kFitTol, kAgreeTol},
        FamilyCase{"Spd", Family::spd, 0.0, 2, kFitTol, kAgreeTol},
        FamilyCase{"DegenerateDiagonallyDominant", Family::dominant, 1.0 / 3.0, 3, kFitTol, kAgreeTol},
        FamilyCase{"DegenerateSpd", Family::spd, 1.0 / 3.0, 3, kFitTol, kAgreeTol},
        FamilyCase{"RankDeficientSemidefinite", Family::rank_deficient, 0.0, 4, kFitTolRankDeficient, 0.0},
        FamilyCase{"DegenerateRankDeficientSemidefinite", Family::rank_deficient, 1.0 / 3.0, 4,
                   kFitTolRankDeficient, 0.0},
        FamilyCase{"NearSingular", Family::near_singular, 0.0, 5, kFitTol, kAgreeTolNearSingular},
        FamilyCase{"DegenerateNearSingular", Family::near_singular, 1.0 / 3.0, 5, kFitTol, kAgreeTolNearSingular}),
    [](const ::testing::TestParamInfo<FamilyCase>& row) { return std::string(row.param.name); });

// W^T M^-1 W of n contacts between n + 1 bodies in a row (a wall at the left end),
// masses spread over a decade: tridiagonal, SPD.
MatrixXd chain_delassus(Gen& g, Index n) {
  VectorXd inv_m(n + 1);
  for (Index i = 0; i <= n; ++i) inv_m(i) = std::exp(-g.uniform(-1.15, 1.15));
  inv_m(0) = 0.0;  // the wall
  MatrixXd a = MatrixXd::Zero(n, n);
  for (Index j = 0; j < n; ++j) {
    a(j, j) = inv_m(j) + inv_m(j + 1);
    if (j + 1 < n) a(j, j + 1) = a(j + 1, j) = -inv_m(j + 1);
  }
  return a;
}

TEST(LcpLemke, SolvesChainSizedProblems) {
  // Up to 100 contacts, beyond enumeration: the planted solution is the unique one.
  // Measured: fit 1e-16, z within 1.5e-15; 1e-12 on z leaves room for the condition of
  // longer chains, which grows like n^2.
  Gen g(15);
  LemkeWorkspace ws;
  double worst_fit = 0.0, worst_z = 0.0;
  int max_pivots = 0;
  for (Index n : {20, 50, 100}) {
    VectorXd z(n);
    for (int t = 0; t < 20; ++t) {
      const Problem p = g.planted(t % 2 ? chain_delassus(g, n) : g.spd(n), t % 4 < 2 ? 0.0 : 0.2);
      const LemkeResult r = lemke(p.a, p.q, z, ws);
      ASSERT_EQ(r.status, Status::solved);
      max_pivots = std::max(max_pivots, r.pivots);
      worst_fit = std::max(worst_fit, fit(p.a, p.q, z).worst());
      worst_z = std::max(worst_z, rel_diff(z, p.z));
    }
  }
  record("chain_fit", worst_fit);
  record("chain_vs_planted", worst_z);
  record("chain_max_pivots", max_pivots);
  EXPECT_LE(worst_fit, kFitTol);
  EXPECT_LE(worst_z, 1e-12);
}

TEST(LcpLemke, SolvesMonotoneNonsymmetricProblems) {
  // A = B B^T + S, S skew: positive semi-definite but not symmetric (copositive-plus),
  // for which Lemke must find a solution when one exists.
  Gen g(6);
  LemkeWorkspace ws;
  double worst = 0.0;
  for (Index n = 1; n <= kMaxSize; ++n) {
    VectorXd z(n);
    for (int t = 0; t < kPerSize; ++t) {
      const MatrixXd s = g.normal(n, n);
      const Problem p = g.planted(g.rank_deficient(n) + (s - s.transpose()), 0.25);
      ASSERT_EQ(lemke(p.a, p.q, z, ws).status, Status::solved);
      worst = std::max(worst, fit(p.a, p.q, z).worst());
    }
  }
  record("monotone_fit", worst);
  // Measured 7e-16 (1.2e-14 before the polish); the rank-deficient allowance, since the
  // symmetric part is the rank-deficient family's.
  EXPECT_LE(worst, kFitTolRankDeficient);
}

TEST(LcpLemke, EndsOnARayWhenNoSolutionExists) {
  LemkeWorkspace ws;
  {
    // w = 0 z - 1 < 0 for every z.
    VectorXd z(1);
    EXPECT_EQ(lemke(MatrixXd::Zero(1, 1), -VectorXd::Ones(1), z, ws).status, Status::no_solution);
    EXPECT_EQ(enumerate(MatrixXd::Zero(1, 1), -VectorXd::Ones(1)).status, Status::no_solution);
  }
  // A = B B^T with B's columns orthogonal to 1: 1^T w = 1^T q for every z, so a q with
  // negative sum leaves some w_i < 0 whatever z is.
  Gen g(7);
  for (Index n = 2; n <= kMaxSize; ++n) {
    VectorXd z(n);
    for (int t = 0; t < 20; ++t) {
      MatrixXd b = g.normal(n, n - 1);
      b.rowwise() -= b.colwise().mean();
      const MatrixXd a = b * b.transpose();
      VectorXd q = g.normal(n, 1);
      q.array() -= q.mean() + 0.5;
      EXPECT_EQ(lemke(a, q, z, ws).status, Status::no_solution);
      EXPECT_EQ(enumerate(a, q).status, Status::no_solution);
    }
  }
}

// Lemke on the tableau [I, -M, -1, q] without the lexicographic rule: ties in the ratio
// test go to the smallest row index. Returns the pivots taken, or -1 at the cap.
int lemke_smallest_index(const MatrixXd& m, const VectorXd& q, int cap) {
  const Index n = q.size();
  MatrixXd t(n, 2 * n + 2);
  t << MatrixXd::Identity(n, n), -m, -VectorXd::Ones(n), q;
  std::vector<Index> basic(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) basic[static_cast<std::size_t>(i)] = i;
  Index r = 0;
  for (Index i = 1; i < n; ++i)
    if (q(i) < q(r)) r = i;
  Index entering = 2 * n;
  for (int pivots = 1; pivots <= cap; ++pivots) {
    t.row(r) /= t(r, entering);
    for (Index i = 0; i < n; ++i)
      if (i != r) t.row(i) -= t(i, entering) * t.row(r);
    const Index leaving = basic[static_cast<std::size_t>(r)];
    basic[static_cast<std::size_t>(r)] = entering;
    if (leaving == 2 * n) return pivots;
    entering = leaving < n ? leaving + n : leaving - n;
    r = -1;
    for (Index i = 0; i < n; ++i) {
      if (t(i, entering) <= 1e-12) continue;
      if (r < 0 || t(i, 2 * n + 1) / t(i, entering) < t(r, 2 * n + 1) / t(r, entering) - 1e-12) r = i;
    }
    if (r < 0) return -1;
  }
  return -1;
}

TEST(LcpLemke, TerminatesOnMurtysCyclingExample) {
  // Murty's degenerate example: every ratio test ties, and the smallest-index rule
  // returns to an earlier basis every six pivots, forever.
  MatrixXd m(3, 3);
  m << 1, 2, 0, 0, 1, 2, 2, 0, 1;
  const VectorXd q = -VectorXd::Ones(3);
  ASSERT_EQ(lemke_smallest_index(m, q, 1000), -1);

  LemkeWorkspace ws;
  VectorXd z(3);
  const LemkeResult r = lemke(m, q, z, ws);
  ASSERT_EQ(r.status, Status::solved);
  EXPECT_LE(r.pivots, 10);
  EXPECT_LE(fit(m, q, z).worst(), kFitTol);
  // The only solution: z = (1, 1, 1) / 3, w = 0 (M is a P-matrix: det M = 9 and every
  // principal minor is positive).
  EXPECT_LE(rel_diff(z, VectorXd::Constant(3, 1.0 / 3.0)), kAgreeTol);
}

TEST(LcpLemkeLex, ReturnsTheSolutionPolynomialOfAPlantedLexicographicProblem) {
  // z(s) = Z0 + s Z1 + s^2 Z2, w(s) likewise, with each component either z or w and its
  // first non-zero coefficient (order 0, 1 or 2) positive; Q = W - A Z. For a P-matrix
  // z(s) is the unique solution for every small s > 0, so Z itself must come back.
  Gen g(8);
  LemkeWorkspace ws;
  double worst_z = 0.0, worst_at_s = 0.0;
  int wrong_active = 0;
  constexpr Index k = 3;
  for (Index n = 1; n <= kMaxSize; ++n) {
    MatrixXd zl(n, k);
    for (int t = 0; t < kPerSize; ++t) {
      const MatrixXd a = t % 2 ? g.spd(n) : g.diagonally_dominant(n);
      MatrixXd zc = MatrixXd::Zero(n, k), wc = MatrixXd::Zero(n, k);
      std::vector<bool> on_z(static_cast<std::size_t>(n));
      for (Index i = 0; i < n; ++i) {
        on_z[static_cast<std::size_t>(i)] = g.uniform(0.0, 1.0) < 0.5;
        const auto order = static_cast<Index>(g.uniform(0.0, 3.0));
        MatrixXd& side = on_z[static_cast<std::size_t>(i)] ? zc : wc;
        side(i, order) = g.uniform(0.5, 2.0);
        for (Index c = order + 1; c < k; ++c) side(i, c) = g.normal();
      }
      const MatrixXd q = wc - a * zc;
      ASSERT_EQ(lemke_lex(a, q, zl, ws).status, Status::solved);
      worst_z = std::max(worst_z, (zl - zc).cwiseAbs().maxCoeff() / std::max(1.0, zc.cwiseAbs().maxCoeff()));
      for (Index i = 0; i < n; ++i)
        if (ws.z_basic(i) != on_z[static_cast<std::size_t>(i)]) ++wrong_active;
      // Cross-check one s against enumeration of the plain LCP(A, q(s)).
      const double s = 1e-3;
      const VectorXd qs = q.col(0) + s * q.col(1) + s * s * q.col(2);
      const EnumerateResult er = enumerate(a, qs);
      ASSERT_EQ(er.status, Status::solved);
      const VectorXd zs = zl.col(0) + s * zl.col(1) + s * s * zl.col(2);
      worst_at_s = std::max(worst_at_s, rel_diff(zs, er.z));
    }
  }
  record("lex_vs_planted", worst_z);
  record("lex_vs_enum_at_s", worst_at_s);
  EXPECT_LE(worst_z, kAgreeTol);
  EXPECT_LE(worst_at_s, kAgreeTol);
  EXPECT_EQ(wrong_active, 0);
}

TEST(LcpLemkeLex, FirstNonVanishingDerivativeDecidesTheActiveSet) {
  // Three bodies in a row, both contacts closed and at rest (q = 0); the load rate
  // pushes contact 0 shut and pulls contact 1 open. The plain LCP(A, 0) is solved by
  // z = 0 with every contact inactive; the lexicographic one keeps contact 0.
  const double m0 = 1.0, m1 = 2.0, m2 = 0.5;
  MatrixXd a(2, 2);
  a << 1 / m1 + 1 / m0, -1 / m0, -1 / m0, 1 / m0 + 1 / m2;
  MatrixXd q(2, 2);
  q << 0.0, -1.0, 0.0, 1.0;
  LemkeWorkspace ws;
  VectorXd z(2);
  ASSERT_EQ(lemke(a, q.col(0), z, ws).status, Status::solved);
  EXPECT_FALSE(ws.z_basic(0));
  MatrixXd zl(2, 2);
  ASSERT_EQ(lemke_lex(a, q, zl, ws).status, Status::solved);
  EXPECT_TRUE(ws.z_basic(0));
  EXPECT_FALSE(ws.z_basic(1));
  // z(s) = s / a00 on contact 0, and w1(s) = s (1 + 1 / (m0 a00)) > 0 on contact 1.
  EXPECT_NEAR(zl(0, 1), 1.0 / a(0, 0), 1e-15);
  EXPECT_EQ(zl(1, 1), 0.0);
  EXPECT_EQ(zl.col(0).cwiseAbs().maxCoeff(), 0.0);
}

TEST(LcpLemke, ReusesWorkspaceStorageForProblemsOfTheSameSize) {
  Gen g(9);
  LemkeWorkspace ws;
  VectorXd z(8);
  const Problem p1 = g.planted(g.spd(8), 0.0), p2 = g.planted(g.spd(8), 0.0);
  ASSERT_EQ(lemke(p1.a, p1.q, z, ws).status, Status::solved);
  const double* binv = ws.binv.data();
  const double* x = ws.x.data();
  ASSERT_EQ(lemke(p2.a, p2.q, z, ws).status, Status::solved);
  EXPECT_EQ(ws.binv.data(), binv);
  EXPECT_EQ(ws.x.data(), x);
  EXPECT_LE(rel_diff(z, p2.z), kAgreeTol);
}

TEST(LcpLemke, RejectsNonFiniteInput) {
  LemkeWorkspace ws;
  VectorXd z(2);
  MatrixXd a = MatrixXd::Identity(2, 2);
  a(0, 1) = std::nan("");
  EXPECT_EQ(lemke(a, -VectorXd::Ones(2), z, ws).status, Status::bad_input);
  EXPECT_EQ(enumerate(a, -VectorXd::Ones(2)).status, Status::bad_input);
}

TEST(LcpEnumerate, RejectsProblemsAboveItsSizeLimit) {
  const Index n = kEnumerateMaxSize + 1;
  EXPECT_EQ(enumerate(MatrixXd::Identity(n, n), -VectorXd::Ones(n)).status, Status::bad_input);
}

// A posteriori bound for SPD A (strongly monotone): in the variables u = D^1/2 z, with
// D = diag(A) and A' = D^-1/2 A D^-1/2, ||u - u*|| <= (1 + ||A'||) / lambda_min(A')
// ||min(u, A' u + q')||, and min(u, A' u + q') = D^-1/2 min(D z, w).
double pgs_error_bound(const MatrixXd& a, const VectorXd& q, const VectorXd& z) {
  const VectorXd d_isqrt = a.diagonal().cwiseSqrt().cwiseInverse();
  const MatrixXd as = d_isqrt.asDiagonal() * a * d_isqrt.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(as);
  const double lo = eig.eigenvalues().minCoeff(), hi = eig.eigenvalues().maxCoeff();
  const VectorXd r = (a.diagonal().cwiseProduct(z)).cwiseMin(a * z + q);
  return d_isqrt.maxCoeff() * (1.0 + hi) / lo * d_isqrt.cwiseProduct(r).norm();
}

TEST(LcpPgs, ConvergesToTheEnumerationAnswerOnSpdProblems) {
  // Within the a posteriori bound of its residual tolerance (1e-12, a few hundred
  // sweeps), plus 1e-13 for the enumeration's own rounding.
  Gen g(10);
  PgsSettings ps;
  ps.tol = 1e-12;
  ps.max_sweeps = 100000;
  int max_sweeps = 0;
  double worst_ratio = 0.0;
  for (Index n = 1; n <= kMaxSize; ++n) {
    for (int t = 0; t < kPerSize; ++t) {
      const Problem p = g.planted(g.spd(n), t % 3 == 0 ? 1.0 / 3.0 : 0.0);
      VectorXd z = VectorXd::Zero(n);
      const PgsResult r = pgs(p.a, p.q, z, ps);
      ASSERT_EQ(r.status, Status::solved);
      EXPECT_LE(r.residual, ps.tol);
      max_sweeps = std::max(max_sweeps, r.sweeps);
      const EnumerateResult er = enumerate(p.a, p.q);
      ASSERT_EQ(er.status, Status::solved);
      const double allowed = pgs_error_bound(p.a, p.q, z) + 1e-13 * std::max(1.0, max_abs(er.z));
      worst_ratio = std::max(worst_ratio, (z - er.z).norm() / allowed);
    }
  }
  record("pgs_error_over_bound", worst_ratio);
  record("pgs_max_sweeps", max_sweeps);
  EXPECT_LE(worst_ratio, 1.0);
}

TEST(LcpPgs, FixedSizeVersionConvergesLikeTheDynamicOne) {
  Gen g(11);
  PgsSettings ps;
  ps.tol = 1e-12;
  ps.max_sweeps = 100000;
  for (int t = 0; t < kPerSize; ++t) {
    const Problem p = g.planted(g.spd(4), 0.25);
    const Eigen::Matrix4d a = p.a;
    const Eigen::Vector4d q = p.q;
    Eigen::Vector4d z4 = Eigen::Vector4d::Zero();
    VectorXd z = VectorXd::Zero(4);
    const PgsResult r4 = pgs<4>(a, q, z4, ps);
    const PgsResult r = pgs(Eigen::Ref<const MatrixXd>(p.a), p.q, z, ps);
    ASSERT_EQ(r4.status, Status::solved);
    ASSERT_EQ(r.status, Status::solved);
    // The same arithmetic up to the order of the dot products: same sweeps, z equal to
    // well inside the residual tolerance.
    EXPECT_NEAR(r4.sweeps, r.sweeps, 1);
    EXPECT_LE(max_abs(VectorXd(z4) - z), 1e-11);
    EXPECT_LE(max_abs(VectorXd(z4) - p.z), pgs_error_bound(p.a, p.q, z) + 1e-13);
  }
}

TEST(LcpPgs, WarmStartAtTheSolutionStopsAfterOneSweep) {
  Gen g(12);
  const Problem p = g.planted(g.spd(6), 0.0);
  VectorXd z = enumerate(p.a, p.q).z;
  PgsSettings ps;
  ps.tol = 1e-12;
  const PgsResult r = pgs(p.a, p.q, z, ps);
  EXPECT_EQ(r.status, Status::solved);
  EXPECT_EQ(r.sweeps, 1);
}

TEST(LcpPgs, ReportsTheCapWhenItCannotConverge) {
  // A chain of 10 contacts, all closed: slow convergence (spectral radius near 1).
  const Index n = 10;
  MatrixXd a = MatrixXd::Zero(n, n);
  for (Index i = 0; i < n; ++i) {
    a(i, i) = 2.0;
    if (i + 1 < n) a(i, i + 1) = a(i + 1, i) = -1.0;
  }
  VectorXd z = VectorXd::Zero(n);
  PgsSettings ps;
  ps.max_sweeps = 5;
  const PgsResult r = pgs(a, -VectorXd::Ones(n), z, ps);
  EXPECT_EQ(r.status, Status::iteration_cap);
  EXPECT_EQ(r.sweeps, 5);
  EXPECT_GT(r.residual, ps.tol);
}

TEST(LcpPgs, RejectsANonPositiveDiagonal) {
  MatrixXd a = MatrixXd::Identity(2, 2);
  a(1, 1) = 0.0;
  VectorXd z = VectorXd::Zero(2);
  EXPECT_EQ(pgs(a, -VectorXd::Ones(2), z).status, Status::bad_input);
}

TEST(LcpSmall, Solve1AgreesWithEnumeration) {
  Gen g(13);
  for (int t = 0; t < kPerSize; ++t) {
    const double a = std::exp(g.uniform(-3.0, 3.0)), q = t % 10 == 0 ? 0.0 : g.normal();
    const EnumerateResult er = enumerate(MatrixXd::Constant(1, 1, a), VectorXd::Constant(1, q));
    ASSERT_EQ(er.status, Status::solved);
    // Both compute -q / a: identical.
    EXPECT_EQ(solve1(a, q), er.z(0));
  }
}

TEST(LcpSmall, Solve2AgreesWithEnumerationOnPMatrices) {
  // Cramer's rule against LU on matrices of condition <= ~1e4: 1e-11 relative.
  Gen g(14);
  double worst = 0.0;
  for (int t = 0; t < 3 * kPerSize; ++t) {
    Eigen::Matrix2d a;
    switch (t % 3) {
      case 0: {  // W^T M^-1 W of three bodies in a row, masses over two decades
        const double m0 = std::exp(g.uniform(-2.3, 2.3)), m1 = std::exp(g.uniform(-2.3, 2.3)),
                     m2 = std::exp(g.uniform(-2.3, 2.3));
        a << 1 / m1 + 1 / m0, -1 / m0, -1 / m0, 1 / m0 + 1 / m2;
        break;
      }
      case 1: a = g.spd(2); break;
      default: a = g.diagonally_dominant(2); break;
    }
    Eigen::Vector2d q(g.normal(), g.normal());
    if (t % 7 == 0) q(t % 2) = 0.0;
    const Eigen::Vector2d z = solve2(a, q);
    const EnumerateResult er = enumerate(a, q);
    ASSERT_EQ(er.status, Status::solved);
    worst = std::max(worst, rel_diff(z, er.z));
  }
  record("solve2_vs_enum", worst);
  EXPECT_LE(worst, 1e-11);
}

}  // namespace lcp_tests
}  // namespace pb::lcp
