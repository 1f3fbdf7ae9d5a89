#pragma once
// Reading the time-steppers' History in tests: one row at a time, by column meaning.

#include <cstddef>

#include "cases/system.hpp"
#include "solvers/solver.hpp"

namespace pb::test {

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
