// The event-driven reference on the N-body chain: Newton's-cradle starts against Poisson's
// law worked out by hand, long chains under the pulse against the stress checks (gap,
// energy balance, restitution), and the 2-chain against the mirrored pair.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "cases/system.hpp"
#include "solvers/event_driven/event_driven.hpp"
#include "kit/testing.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace chain_reference_tests {

Case chain_case(int n, double pi3, double eps, double kick, double pi5 = 1.0, double pi6 = 1.0) {
  Case c;
  c.scene = Scene::chain;
  c.bodies = n;
  c.pi2 = 1.0;
  c.pi3 = pi3;
  c.eps = eps;
  c.kick = kick;
  c.pi5 = pi5;
  c.pi6 = pi6;
  return c;
}

// Body velocities at time t (history row at t_end = t), in units of the kick velocity.
std::vector<double> velocities_at(System s, double t, double v0) {
  s.t_end = t;
  Settings st;
  st.history_samples = 2;
  const Result r = event_driven::solve(s, st);
  EXPECT_EQ(r.status, Status::ok) << r.message;
  std::vector<double> v;
  const test::HistoryRow last{r.history, r.history.rows() - 1};
  for (int i = 0; i < s.n_bodies(); ++i) v.push_back(last.v(i) / v0);
  return v;
}

// Touching equal bodies, eps = 1, body 0 struck at v0: the compression brings all N to the
// common velocity v0 / N with impulses that need no expansion impulse (Lambda_P = 0; the
// expansion LCP's right-hand side eps G Lambda_C = -gd_A is >= 0), so the total impulse is
// twice the compression one: v_0 = v0 - 2 (v0 - v0/N) = (2 - N)/N v0, every other body
// 2 v0 / N. Energy is kept: ((N - 2)^2 + 4 (N - 1)) / N^2 = 1. The history's first row is
// the state just after the impact at t = 0.
TEST(ChainReference, TouchingNewtonsCradleSharesTheBlowByPoissonsLaw) {
  for (int n : {3, 10, 100}) {
    const System s = make_system(chain_case(n, 0.0, 1.0, 100.0));
    Settings st;
    st.history_samples = 2;
    const Result r = event_driven::solve(s, st);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    const test::HistoryRow first{r.history, 0};
    ASSERT_EQ(first.t(), 0.0);
    const double v0 = s.v_start[0];
    // 1e-12: the impulses of a run are one tridiagonal solve (rounding only).
    EXPECT_NEAR(first.v(0) / v0, (2.0 - n) / n, 1e-12) << "N = " << n;
    for (int i = 1; i < n; ++i) EXPECT_NEAR(first.v(i) / v0, 2.0 / n, 1e-12) << "N = " << n << " body " << i;
  }
}

// With a gap the impacts come one at a time, each an elastic exchange between equal
// masses: the far end leaves at v0, the others stop. Read just after the last impact
// (2 N delta / v0), before the springs and the pulse (a_p over 2e-7 / w_p: 2e-9 of v0)
// have moved anything.
TEST(ChainReference, NewtonsCradleWithAGapPassesTheBlowToTheFarEnd) {
  for (int n : {3, 10}) {
    const System s = make_system(chain_case(n, 1e-6, 1.0, 100.0));
    const double v0 = s.v_start[0];
    const std::vector<double> v = velocities_at(s, 2.0 * n * s.delta / v0, v0);
    // 1e-6: what the springs and the pulse add over the window (measured 2e-8).
    EXPECT_NEAR(v[static_cast<std::size_t>(n - 1)], 1.0, 1e-6) << "N = " << n;
    for (int i = 0; i + 1 < n; ++i) EXPECT_NEAR(v[static_cast<std::size_t>(i)], 0.0, 1e-6) << "N = " << n << " body " << i;
  }
}

// The stress checks on a long alternating chain under the pulse (no kick, and a kick that
// breaks the symmetry of even and odd bodies). Tolerances: a gap goes below zero by at
// most the closure tolerance (1e-10 of the pulse length); the energy balance moves only by
// rounding at events (measured <= 2e-14; 1e-9 is the stress check's round-off bound); a
// single-contact impact is Newton's law, measured e within 1e-13 of eps (rounding of
// velocities ~1e3 times the slowest counted approach).
TEST(ChainReference, HundredAlternatingBodiesUnderThePulseKeepGapEnergyAndRestitution) {
  for (double eps : {0.5, 1.0}) {
    for (double kick : {0.0, 1.0}) {
      Case c = chain_case(100, 0.5, eps, kick, 2.0, 0.5);
      c.pulse = kick > 0.0 ? PulseShape::sine : PulseShape::cosine;
      const System s = make_system(c);
      const Result r = event_driven::solve(s, {});
      ASSERT_EQ(r.status, Status::ok) << r.message;
      EXPECT_GT(r.impacts, 1000);
      EXPECT_GT(r.min_gap, -1.01e-10 * s.length_scale());
      EXPECT_LE(r.energy_excess, 1e-9);
      ASSERT_GT(r.isolated_impacts, 100);
      EXPECT_NEAR(r.restitution_low, eps, 1e-11);
      EXPECT_NEAR(r.restitution_high, eps, 1e-11);
    }
  }
}

// Touching at rest with a kick: long runs of persistent contact are decided without
// enumerating their 2^99 active sets, and impacts propagate through them.
TEST(ChainReference, TouchingAlternatingChainOfHundredFinishes) {
  const System s = make_system(chain_case(100, 0.0, 0.5, 1.0, 2.0, 0.5));
  const Result r = event_driven::solve(s, {});
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_GT(r.contact_phases, 100);
  EXPECT_GT(r.min_gap, -1.01e-10 * s.length_scale());
  EXPECT_LE(r.energy_excess, 1e-9);
}

// Solves the chains below both ways (alternating bodies, apart and touching, with
// persistent contact, with and without a kick, N = first_n, 8, 30) and compares: the same
// status and impacts, Pi1 within `bound`; a touching elastic chain (a Newton's cradle under
// the pulse), whose near-simultaneous impacts come in an order that round-off decides, within
// the stored baselines' 1e-9 and 1 % of the impacts. Returns the largest relative change of
// Pi1 outside those, and adds the impacts to `impacts`.
template <class A, class B>
double compare_chains(int first_n, A&& solve_a, B&& solve_b, double bound, long& impacts) {
  double worst = 0.0;
  for (int n : {first_n, 8, 30}) {
    for (double pi3 : {0.0, 0.5}) {
      for (double eps : {0.0, 0.6, 1.0}) {
        for (double kick : {0.0, 1.0}) {
          if (pi3 == 0.0 && kick == 0.0) continue;  // touching at rest: they stay together
          Case c = chain_case(n, pi3, eps, kick, 2.0, 0.5);  // alternating bodies
          c.pulse = n == 8 ? PulseShape::cosine : PulseShape::sine;
          const System s = make_system(c);
          const Result a = solve_a(s, Settings{}), b = solve_b(s, Settings{});
          const std::string which = "N = " + std::to_string(n) + ", Pi3 = " + std::to_string(pi3) +
                                    ", eps = " + std::to_string(eps) + ", kick = " + std::to_string(kick);
          EXPECT_EQ(a.status, Status::ok) << which << ": " << a.message;
          EXPECT_EQ(b.status, Status::ok) << which << ": " << b.message;
          const bool cradle = pi3 == 0.0 && eps == 1.0;
          if (cradle) {
            EXPECT_LE(std::abs(a.impacts - b.impacts), b.impacts / 100) << which;
          } else {
            EXPECT_EQ(a.impacts, b.impacts) << which;
            worst = std::max(worst, std::abs(a.pi1 - b.pi1) / std::abs(b.pi1));
          }
          EXPECT_NEAR(a.pi1, b.pi1, (cradle ? 1e-9 : bound) * std::abs(b.pi1)) << which;
          EXPECT_LE(a.energy_excess, 1e-12) << which;
          impacts += b.impacts;
        }
      }
    }
  }
  return worst;
}

// A contact whose bodies an event did not move keeps its last search's answer instead of
// being searched again (DERIVATION.md §9). Its wave is rebuilt all the same, the same motion
// to round-off, so the answers are those of searching every contact at every event to
// round-off: Pi1 within 1e-13 (measured: at most 4e-15 here and 2.8e-15 on the stress set)
// and the same impacts; touching elastic chains as compare_chains says (measured 7.3e-12
// and 1163 impacts against 1161 at N = 30).
TEST(ChainReference, KeptSearchesGiveTheAnswersOfSearchingEveryContact) {
  long impacts = 0;
  compare_chains(3, event_driven::detail::solve_rebuilding_every_body,
                 event_driven::detail::solve_searching_every_contact, 1e-13, impacts);
  EXPECT_GT(impacts, 1000);  // events enough for kept searches to matter
}

// An event rebuilds only the clusters it changes and takes the other bodies' states from
// the waves they kept (DERIVATION.md §9): the same motions, anchored at an earlier event, so
// the answers are those of rebuilding every body at every event to round-off. Measured over
// these chains: Pi1 within 2.5e-14 (held to 1e-12) and the same impacts.
TEST(ChainReference, LazyEventsGiveTheAnswersOfRebuildingEveryBody) {
  long impacts = 0;
  const double worst =
      compare_chains(4, event_driven::solve, event_driven::detail::solve_rebuilding_every_body, 1e-12, impacts);
  std::ostringstream out;
  out << worst;
  RecordProperty("worst_relative_pi1", out.str());
  EXPECT_GT(impacts, 1000);
}

// A Newton's cradle (equal bodies touching at rest, eps = 1, body 0 kicked) moves as body 0
// and one cluster of the rest, whose contact forces are zero but for rounding (1e-14 m a_p):
// none of them is an event. Solved eagerly, the first sign change of each force's rounding
// was one, where the contact LCP kept the cluster as it was (167 events for 7 impacts at
// N = 300, Pi2 = 0.1; 381 at N = 1000): its events are its impacts, the pulse's end and
// t_end. Pi1 is the eager one's to round-off.
TEST(ChainReference, ANewtonsCradlesRestingForcesMakeNoEvents) {
  for (int n : {10, 300}) {
    Case c = chain_case(n, 0.0, 1.0, 1.0);
    c.pi2 = 0.1;
    const System s = make_system(c);
    const Result lazy = event_driven::solve(s, {});
    const Result eager = event_driven::detail::solve_rebuilding_every_body(s, {});
    ASSERT_EQ(lazy.status, Status::ok) << lazy.message;
    EXPECT_EQ(lazy.impacts, eager.impacts) << "N = " << n;
    EXPECT_LE(lazy.steps, lazy.impacts + 2) << "N = " << n;
    EXPECT_NEAR(lazy.pi1, eager.pi1, 1e-13 * eager.pi1) << "N = " << n;
  }
}

// A 2-chain (bodies 0, 1 left to right, body 1 with Pi5, Pi6) is the pair (1, 0) seen in a
// mirror, and the mirror turns the load's sign: with opposite directivities the two must
// give the same Pi1. Measured 1.2e-14; the mirror changes only the order of rounding.
TEST(ChainReference, ChainOfTwoIsThePairInAMirror) {
  for (PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
    for (Directivity d : {Directivity::normal, Directivity::reverse}) {
      for (double pi3 : {0.0, 0.5}) {
        for (double eps : {0.0, 0.5, 1.0}) {
          for (double pi2 : {0.4, 2.0}) {
            Case pair = test::make_case(Scene::pair, p, pi2, 2.0, eps);
            pair.directivity = d;
            pair.pi3 = pi3;
            pair.pi6 = 0.5;
            Case chain = pair;
            chain.scene = Scene::chain;
            chain.bodies = 2;
            chain.directivity = d == Directivity::normal ? Directivity::reverse : Directivity::normal;
            const Result a = event_driven::solve(make_system(pair), {});
            const Result b = event_driven::solve(make_system(chain), {});
            ASSERT_EQ(b.status, Status::ok) << b.message;
            EXPECT_NEAR(b.pi1, a.pi1, 1e-12 * a.pi1) << name(p) << " " << name(d) << " pi3=" << pi3 << " eps=" << eps;
            EXPECT_EQ(b.impacts, a.impacts);
          }
        }
      }
    }
  }
}

// The variant "lemke" decides long runs by Lemke's method first, for impacts and for the
// contact LCP, where the default uses Chandrasekaran's method and cheap candidates: two
// independent routes through touching chains, which must agree. Measured 4e-15 (eps < 1);
// with eps = 1 nothing damps rounding and a 30-chain agrees to 1e-11 only, so it is left out.
TEST(ChainReference, LemkeVariantAgreesWithTheDefaultOnTouchingChains) {
  struct Run {
    int n;
    double eps, kick, pi5, pi6, pi2;
    PulseShape pulse;
  };
  for (const Run run : {Run{30, 0.5, 1.0, 2.0, 0.5, 1.0, PulseShape::sine},
                        Run{30, 0.5, 0.0, 2.0, 0.5, 1.0, PulseShape::cosine},
                        Run{12, 1.0, 1.0, 0.5, 2.0, 2.0, PulseShape::sine}}) {
    Case c = chain_case(run.n, 0.0, run.eps, run.kick, run.pi5, run.pi6);
    c.pi2 = run.pi2;
    c.pulse = run.pulse;
    const System s = make_system(c);
    Settings lemke;
    lemke.variant = "lemke";
    ASSERT_EQ(event_driven::check(lemke), "");
    const Result a = event_driven::solve(s, {}), b = event_driven::solve(s, lemke);
    ASSERT_EQ(a.status, Status::ok) << a.message;
    ASSERT_EQ(b.status, Status::ok) << b.message;
    EXPECT_GT(a.contact_phases, 0);
    EXPECT_NEAR(b.pi1, a.pi1, 1e-12 * a.pi1) << "N = " << run.n << " eps = " << run.eps;
  }
}

// The clock is read every few hundred events; a run of more events than that with no time
// to spare stops there, as a timeout, with the Pi1 found so far.
TEST(ChainReference, TimeLimitStopsTheRunAsTimeout) {
  Settings st;
  st.time_limit = 1e-9;
  const Result r = event_driven::solve(make_system(chain_case(100, 0.5, 0.5, 1.0, 2.0, 0.5)), st);
  EXPECT_EQ(r.status, Status::time_limit);
  EXPECT_FALSE(r.message.empty());
  EXPECT_TRUE(std::isnan(r.pi1)) << "a run cut short has no Pi1";
}

}  // namespace chain_reference_tests
}  // namespace pb
