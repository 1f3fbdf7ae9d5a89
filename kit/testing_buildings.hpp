#pragma once
// What the buildings' tests share (tests/buildings_model_test.cpp, the reference's own in
// solvers/buildings_reference/, each engine's): a building from its floors, the issue's pair,
// a shipped set's point, and a result's distance from the reference's.

#include <algorithm>
#include <string_view>
#include <atomic>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include <string>

#include "cases/buildings.hpp"
#include "cases/buildings_set.hpp"
#include "cases/case.hpp"
#include "cases/load.hpp"
#include "cases/record.hpp"
#include "kit/buildings_result.hpp"
#include "kit/fixed_step.hpp"
#include "kit/testing.hpp"

namespace pb::test {

inline Building building(std::vector<double> m, std::vector<double> k) { return {std::move(m), std::move(k)}; }

// The issue's two buildings (three storeys each, SI units), 5 % Rayleigh damping, a 30 mm gap,
// eps 0.6, under a sine pulse of 3 m/s^2 at 2 Hz.
inline BuildingScene issue_scene() {
  BuildingScene s;
  s.buildings = {building({3e5, 3e5, 2.4e5}, {6.8e8, 5.4e8, 4.1e8}), building({2.5e5, 2.5e5, 2e5}, {2.0e8, 1.6e8, 1.2e8})};
  s.xi = 0.05;
  s.delta = 0.03;
  s.eps = 0.6;
  s.pulse = Pulse(PulseShape::sine, 3.0, 12.566);
  return s;
}

// The issue's pair at a 10 mm gap under a short synthetic record (61 samples 0.02 s apart, a
// decaying sine of 3 m/s^2), on the scales a_p = 3, w_p = 12.566: a record's load through a
// buildings solver.
inline BuildingScene issue_scene_under_a_record() {
  Case c;
  c.pulse = PulseShape::record;
  c.a_p = 3.0;
  c.w_p = 12.566;
  auto rec = std::make_shared<Record>();
  rec->source = "synthetic";
  for (int i = 0; i <= 60; ++i) {
    rec->t.push_back(0.02 * i);
    rec->a.push_back(i == 0 ? 0.0 : 3.0 * std::sin(0.5 * i) * std::exp(-0.03 * i));
    rec->peak = std::max(rec->peak, std::abs(rec->a.back()));
  }
  c.samples = rec;
  BuildingScene s = issue_scene();
  s.pulse = make_pulse(c);
  s.a_p = c.a_p;
  s.w_p = c.w_p;
  s.delta = 0.01;
  return s;
}

#ifdef POUNDBENCH_SOURCE_DIR
// Point p of a shipped buildings set (cases/sets/NAME), assembled.
inline BuildingModel shipped_point(const char* set, std::size_t p) {
  const auto s = load_buildings_set(std::string(POUNDBENCH_SOURCE_DIR) + "/cases/sets/" + set);
  EXPECT_TRUE(s.has_value());
  EXPECT_LT(p, s->points.size());
  return assemble(s->points.at(p).scene);
}
#endif

// The largest relative error of any floor's peak |u| against the reference's; with `drifts`,
// of any storey's peak |drift| too.
inline double floor_error(const buildings::BuildingsResult& r, const buildings::BuildingsResult& ref,
                          bool drifts = false) {
  double e = 0.0;
  for (std::size_t b = 0; b < ref.floor_peak.size(); ++b)
    for (std::size_t i = 0; i < ref.floor_peak[b].size(); ++i) {
      e = std::max(e, rel(r.floor_peak[b][i], ref.floor_peak[b][i]));
      if (drifts) e = std::max(e, rel(r.drift_peak[b][i], ref.drift_peak[b][i]));
    }
  return e;
}

// How many floor contacts took an impact.
inline int floors_hit(const buildings::BuildingsResult& r) {
  int n = 0;
  for (const auto& c : r.contacts) n += c.impacts > 0 ? 1 : 0;
  return n;
}

// What every engine's buildings solve does with a run that cannot finish, on the issue's pair: a
// step past the explicit storeys' limit (w_max h = 3, above ~1.9) diverges; one longer than the
// pulse period is refused before the run; the time limit and the stop flag end it early; an
// unknown variant is refused in one line naming the engine's default.
inline void expect_buildings_statuses(buildings::BuildingsResult (*solve)(const BuildingModel&, const Settings&),
                                      std::string_view default_variant) {
  const BuildingModel md = assemble(issue_scene());
  Settings unstable;
  unstable.wh = 3.0;
  const buildings::BuildingsResult d = solve(md, unstable);
  EXPECT_EQ(d.status, Status::diverged) << d.message;
  EXPECT_NE(d.message.find("at step"), std::string::npos) << d.message;
  EXPECT_GT(d.events, 0);

  Settings far;
  far.wh = 100.0;
  const buildings::BuildingsResult f = solve(md, far);
  EXPECT_EQ(f.status, Status::failed);
  EXPECT_TRUE(f.message.starts_with(kStepBoundMessage)) << f.message;
  EXPECT_EQ(f.events, 0);

  Settings limited;
  limited.steps = 4096;
  limited.time_limit = 1e-9;
  const buildings::BuildingsResult late = solve(md, limited);
  EXPECT_EQ(late.status, Status::time_limit) << late.message;
  EXPECT_GT(late.events, 0);
  EXPECT_LT(late.events, step_count(md.t_end, late.step));

  const std::atomic<bool> stop{true};
  Settings stopped;
  stopped.stop = &stop;
  const buildings::BuildingsResult halted = solve(md, stopped);
  EXPECT_EQ(halted.status, Status::time_limit) << halted.message;
  EXPECT_NE(halted.message.find("stopped"), std::string::npos) << halted.message;

  Settings unknown;
  unknown.variant = "pgs";
  const buildings::BuildingsResult u = solve(md, unknown);
  EXPECT_EQ(u.status, Status::failed);
  EXPECT_NE(u.message.find("pgs"), std::string::npos) << u.message;
  EXPECT_NE(u.message.find(default_variant), std::string::npos) << u.message;
  EXPECT_EQ(u.message.find('\n'), std::string::npos) << u.message;
}

}  // namespace pb::test
