#pragma once
// What the buildings' tests share (tests/buildings_model_test.cpp, the reference's own in
// solvers/buildings_reference/): a building from its floors, and the issue's pair.

#include <utility>
#include <vector>

#include "cases/buildings.hpp"

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

}  // namespace pb::test
