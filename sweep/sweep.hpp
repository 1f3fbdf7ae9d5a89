#pragma once
// Runs one solver over a list of cases on several threads and collects result rows.
//
// Points are handed out one at a time from a shared counter (dynamic scheduling): the cost
// of a point ranges over orders of magnitude (a stiff body or many impacts), so a static
// split would leave threads idle. Rows complete out of order; the callbacks see them in
// completion order and run_sweep returns them in point order.
//
// Thread safety: SolverInfo::solve and describe are called from several threads at once,
// with the same Settings, so a solver must be reentrant (no mutable globals or statics);
// every solver of the registry is. The callbacks are never called concurrently.

#include <atomic>
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "cases/case.hpp"
#include "solvers/solver.hpp"
#include "sweep/row.hpp"

namespace pb {

// Solves one case: builds the System, times solver.solve alone, adds the no-contact Pi1.
// Never throws for a bad case or a throwing solver: the row then has Status::failed and
// the reason in its message.
Row run_point(const Case& c, std::size_t point, const SolverInfo& solver, const Settings& settings);

struct SweepOptions {
  unsigned threads = 0;  // 0: std::thread::hardware_concurrency()
  // Called once per finished row, in completion order. An exception thrown here stops
  // the sweep (no new points start) and is rethrown by run_sweep.
  std::function<void(const Row&)> on_row;
  // Called after on_row with the number of rows done so far and the number of cases.
  std::function<void(std::size_t done, std::size_t total)> on_progress;
  // When set to true, no new point starts; the points already running finish and are
  // reported. run_sweep then returns the rows it has (fewer than the cases).
  const std::atomic<bool>* cancel = nullptr;
};

// Rows sorted by point index: one per case unless the sweep was cancelled.
std::vector<Row> run_sweep(std::span<const Case> cases, const SolverInfo& solver, const Settings& settings,
                           const SweepOptions& options = {});

}  // namespace pb
