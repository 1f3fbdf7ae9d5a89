#pragma once
// What the buildings' tests share (tests/buildings_model_test.cpp, the reference's own in
// solvers/buildings_reference/): a building from its floors, and the issue's pair.

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "cases/buildings.hpp"
#include "cases/case.hpp"
#include "cases/load.hpp"
#include "cases/record.hpp"

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

}  // namespace pb::test
