#pragma once
// What the solver tests share: the paper's standard pair/row3 case, reading a time-stepper's
// History one row at a time, by column meaning, the measured-number format, the observed
// order of a list of errors, the cradle start, the stress monitor's cases and what it
// measures on them, the convergence set, free bodies at the wall and in a pair, an engine's
// variant by name, and check()'s refusal of one changed setting.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "cases/record.hpp"
#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb::test {

// What parse_record says of a record's text: its error's message, or "(accepted)".
inline std::string record_error(std::string_view text, std::string_view source) {
  try {
    parse_record(text, source);
  } catch (const RecordError& e) {
    return e.what();
  }
  return "(accepted)";
}

// A Fig. 4 style case: Pi3 = 0.5, Pi6 = 1; row3 is the symmetric configuration of the paper.
inline Case make_case(Scene scene, PulseShape p, double pi2, double pi5, double eps) {
  Case c;
  c.scene = scene;
  c.pulse = p;
  c.pi2 = pi2;
  c.pi3 = 0.5;
  c.pi5 = pi5;
  c.pi6 = 1.0;
  c.pi7 = pi5;
  c.pi8 = 1.0;
  c.eps = eps;
  return c;
}

// A case whose bodies yield (cases/README.md, "Yielding"): body 0 at Pi_y pi_y, body 1 at
// twice that, body 2 at 1.5 times (a chain: six bodies at pi_y).
inline Case yielding_case(Scene scene, PulseShape pulse, double pi2, double pi5, double eps, double pi_y,
                          double alpha) {
  Case c = make_case(scene, pulse, pi2, pi5, eps);
  if (scene == Scene::chain) {
    c.bodies = 6;
    c.pi_y = pi_y;
  } else {
    c.pi_y0 = pi_y;
    if (scene != Scene::wall) c.pi_y1 = 2.0 * pi_y;
    if (scene == Scene::row3) c.pi_y2 = 1.5 * pi_y;
  }
  c.alpha = alpha;
  return c;
}

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// |a - b| relative to |b|.
inline double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

// A measured number for RecordProperty and messages, in scientific notation (std::to_string
// would print 1e-13 as 0.000000).
inline std::string sci(double x) {
  std::ostringstream out;
  out << std::scientific << std::setprecision(2) << x;
  return out.str();
}

// Least-squares slope of log(err) against log(h), h divided by 2^halvings from one error to
// the next (1: N doubling, 2: N quadrupling).
inline double observed_order(const std::vector<double>& errs, int halvings = 1) {
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  const double n = static_cast<double>(errs.size());
  for (std::size_t i = 0; i < errs.size(); ++i) {
    const double x = halvings * static_cast<double>(i), y = std::log2(errs[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// Newton's cradle start of a uniform chain of n bodies: touching (Pi3 = 0), eps = 1, body 0
// kicked at 100 a_p / w_p, no damping and a sine pulse (zero at t = 0), so that the first
// step carries no force but the contacts'; t_end is one step of N = 64.
inline System cradle(int n) {
  Case c = make_case(Scene::chain, PulseShape::sine, 1.0, 1.0, 1.0);
  c.bodies = n;
  c.pi3 = 0.0;
  c.kick = 100.0;
  c.xi = 0.0;
  System s = make_system(c);
  s.t_end = s.step(64);
  return s;
}

// The stress monitor's cases of the engine tests: wall, pair, row3 and a 6-body chain under
// both pulses (Pi2 = Pi5 = 0.5, eps = 0.5).
inline std::vector<System> monitor_systems() {
  std::vector<System> systems;
  for (Scene scene : {Scene::wall, Scene::pair, Scene::row3, Scene::chain})
    for (PulseShape p : {PulseShape::sine, PulseShape::cosine}) {
      Case c = make_case(scene, p, 0.5, 0.5, 0.5);
      c.bodies = scene == Scene::chain ? 6 : 0;
      systems.push_back(make_system(c));
    }
  return systems;
}

// What the StepMonitor of a faithful time-stepper measures over monitor_systems() at N = 64
// (eps = 0.5): its isolated impacts, their worst |e - eps|, the worst energy excess and, where
// asked, the least ratio of a case's excess at N = 64 to that at N = 1024 (over the cases
// with an excess above 1e-3: the first-order error's drop). Recorded as properties of the
// test under `name`; run(system, N) solves.
struct MonitorSummary {
  long isolated = 0;
  double worst_e = 0.0, worst_excess = 0.0, least_drop = std::numeric_limits<double>::infinity();
};
inline MonitorSummary monitor_summary(std::string_view name, const std::function<Result(const System&, int)>& run,
                                      bool with_drop) {
  MonitorSummary out;
  for (const System& s : monitor_systems()) {
    const Result r = run(s, 64);
    if (r.status != Status::ok) {
      ADD_FAILURE() << name << ": " << r.message;
      continue;
    }
    out.isolated += r.isolated_impacts;
    if (r.isolated_impacts > 0)
      out.worst_e = std::max({out.worst_e, std::abs(r.restitution_low - 0.5), std::abs(r.restitution_high - 0.5)});
    EXPECT_GE(r.energy_excess, 0.0);
    out.worst_excess = std::max(out.worst_excess, r.energy_excess);
    if (with_drop && r.energy_excess > 1e-3)
      out.least_drop = std::min(out.least_drop, r.energy_excess / run(s, 1024).energy_excess);
  }
  const std::string key(name);
  ::testing::Test::RecordProperty(key + "_isolated", std::to_string(out.isolated));
  ::testing::Test::RecordProperty(key + "_restitution_error", sci(out.worst_e));
  ::testing::Test::RecordProperty(key + "_excess_N64", sci(out.worst_excess));
  if (with_drop) ::testing::Test::RecordProperty("least_drop_N64_to_N1024", sci(out.least_drop));
  return out;
}

// The convergence set of the time-stepper tests: pair and symmetric row3 cases of the Fig. 4
// and Fig. 7 families (Pi3 = 0.5, Pi6 = 1, eps = 0.5) under both pulses, Pi5 = 0.5 and 2,
// Pi2 = 0.5, 1 and 2. Those without impacts in the reference tell nothing of the contacts.
inline std::vector<System> convergence_systems() {
  std::vector<System> systems;
  for (Scene scene : {Scene::pair, Scene::row3})
    for (PulseShape p : {PulseShape::sine, PulseShape::cosine})
      for (double pi5 : {0.5, 2.0})
        for (double pi2 : {0.5, 1.0, 2.0}) systems.push_back(make_system(make_case(scene, p, pi2, pi5, 0.5)));
  return systems;
}

// A free body of mass m (w = 1, but no spring, damper or load) at gap g0 from the wall, at
// rest, a_p = w_p = 1 (so that a model built in the pulse's units is built in the case's):
// its only force is the contact's. t_min sets the step (h = t_min / N).
inline System free_body_at_wall(double m, double g0, double eps, double t_min, double t_end) {
  System s;
  s.bodies = {Body{m, 1.0, 0.0, 0.0}};
  s.wall = true;
  s.delta = g0;
  s.eps = eps;
  s.a_p = 1.0;
  s.pulse.amplitude = 0.0;
  s.t_min = t_min;
  s.t_end = t_end;
  return s;
}

// A free mass of 2 coasting at v0 towards the wall from a gap g0: t_min 0.64 (h = 0.01 at
// N = 64); t_end 0.1 past the time it reaches the wall.
inline System free_mass_at_wall(double g0, double eps, double v0) {
  System s = free_body_at_wall(2.0, g0, eps, 0.64, 0.1 + g0 / std::abs(v0));
  s.u_start = {0.0};
  s.v_start = {v0};
  return s;
}

// Two free masses 3:1 (no spring, damper or load) closing at relative speed 2 from a gap of
// 0.033, body 0 at 1 and body 1 at -1: free_mass_at_wall's set-up between two bodies.
inline System free_pair(double eps) {
  System pair = free_mass_at_wall(0.033, eps, 1.0);
  pair.wall = false;
  pair.bodies = {Body{3.0, 1.0, 0.0, 0.0}, Body{1.0, 1.0, 0.0, 0.0}};
  pair.ref = 1;
  pair.u_start = {0.0, 0.0};
  pair.v_start = {1.0, -1.0};
  return pair;
}

// The configuration called `name` in an engine's variant table (kit/variant_table.hpp),
// failing the test where there is none.
template <class Table>
auto config_named(const Table& table, std::string_view name) {
  const auto config = table.find(name);
  EXPECT_TRUE(config.has_value()) << name;
  return config.value_or(typename decltype(config)::value_type{});
}

// check(settings) refuses `base` changed by `change`, naming `field` first ("field: why").
template <class Check, class Change>
void expect_refused(Check check, Settings base, std::string_view field, Change change) {
  change(base);
  const std::string message = check(base);
  EXPECT_EQ(message.rfind(std::string(field) + ":", 0), 0u) << "expected " << field << ": " << message;
}

// solve(s) with a variant, N steps per shortest period (0: the default) and, if asked, every
// step's history.
inline Result run_variant(SolveFn solve, const System& s, std::string_view variant, int n = 0, bool history = false) {
  Settings st;
  st.variant = std::string(variant);
  st.steps = n;
  st.history_samples = history ? 1 : 0;
  return solve(s, st);
}

// Row r of a History: t, u[nb], v[nb], g[nc], lambda[nc] (kit/solver.hpp).
struct HistoryRow {
  const History& h;
  std::size_t r;
  double at(int col) const {
    return h.data[r * static_cast<std::size_t>(h.row_size()) + static_cast<std::size_t>(col)];
  }
  double t() const { return at(0); }
  double u(int i) const { return at(1 + i); }
  double v(int i) const { return at(1 + h.n_bodies + i); }
  double g(int j) const { return at(1 + 2 * h.n_bodies + j); }
  double lambda(int j) const { return at(1 + 2 * h.n_bodies + h.n_contacts + j); }
};

// The one impact of free_mass_at_wall(g0, eps, -1): the approach left at exactly eps times its
// speed. 1e-14: one impulse of O(1) numbers.
inline void expect_free_wall_restituted(const Result& r, double eps, std::string_view variant) {
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_EQ(r.impacts, 1);
  EXPECT_NEAR((HistoryRow{r.history, r.history.rows() - 1}.v(0)), eps, 1e-14) << variant << " eps=" << eps;
}

// Newton's law on free_pair's one impact: the relative velocity reversed by exactly eps and
// the momentum kept. 1e-14: one impulse of O(1) numbers.
inline void expect_free_pair_restituted(const Result& r, double eps, std::string_view variant) {
  ASSERT_EQ(r.status, Status::ok) << r.message;
  EXPECT_EQ(r.impacts, 1);
  const HistoryRow end{r.history, r.history.rows() - 1};
  EXPECT_NEAR(end.v(1) - end.v(0), 2.0 * eps, 1e-14) << variant << " eps=" << eps;
  EXPECT_NEAR(3.0 * end.v(0) + end.v(1), 2.0, 1e-14) << variant << " eps=" << eps;
}

// Gap rate g'_j = v[right] - v[left] of a history row.
inline double gap_rate(const System& s, const HistoryRow& row, int j) {
  const int left = s.left(j);
  return row.v(s.right(j)) - (left == kWall ? 0.0 : row.v(left));
}

}  // namespace pb::test
