#pragma once
// What the solver tests share: the paper's standard pair/row3 case, and reading a
// time-stepper's History one row at a time, by column meaning.

#include <cstddef>

#include "cases/system.hpp"
#include "solvers/solver.hpp"

namespace pb::test {

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

// Row r of a History: t, u[nb], v[nb], g[nc], lambda[nc] (solvers/solver.hpp).
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

// Gap rate g'_j = v[right] - v[left] of a history row.
inline double gap_rate(const System& s, const HistoryRow& row, int j) {
  const int left = s.left(j);
  return row.v(s.right(j)) - (left == kWall ? 0.0 : row.v(left));
}

}  // namespace pb::test
