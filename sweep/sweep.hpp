#pragma once
// Runs solvers over a list of cases on several threads and collects result rows.
//
// A sweep has one or more runs (a solver and its settings), each over every case; a task
// is one (run, point) pair, numbered run * cases + point. Tasks are handed out one at a
// time (dynamic scheduling): the cost of a point ranges over orders of magnitude (a stiff
// body or many impacts), so a static split would leave threads idle. Rows complete out of
// order; the callbacks see them in completion order and run_sweep returns them sorted by
// run, then point.
//
// Which tasks run is the caller's: by default every task in order; a resumed sweep or one
// process of an MPI job (sweep/mpi_sweep.hpp) passes next_task to run only its own.
//
// Thread safety: SolverInfo::solve and describe are called from several threads at once,
// with the same Settings, so a solver must be reentrant (no mutable globals or statics);
// every solver of the registry is. The callbacks are never called concurrently.

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "cases/case.hpp"
#include "solvers/solver.hpp"
#include "rows/row.hpp"

namespace pb {

// Solves one case: builds the System, times solver.solve alone, adds the no-contact Pi1.
// Never throws for a bad case or a throwing solver: the row then has Status::failed and
// the reason in its message.
Row run_point(const Case& c, std::size_t point, const SolverInfo& solver, const Settings& settings);

// One solver with its settings, run over every case of a sweep.
struct SweepRun {
  const SolverInfo* solver = nullptr;
  Settings settings;
};

// Hands out the task a thread solves next; nullopt when there is none left. It is called
// from several threads at once and may block until a task is there.
using TaskSource = std::function<std::optional<std::size_t>()>;

// The order of a sweep's rows: by run, then by point.
bool task_order(const Row& a, const Row& b);

// A TaskSource over a fixed list of tasks, in its order (the list must outlive it).
TaskSource tasks_from(std::span<const std::size_t> tasks);

// The default SweepOptions::point_time_limit: a hundred times the slowest point of the
// shipped sets (a 100-body chain through Bullet's MLCP at the finest stress step, ~0.6 s).
inline constexpr double kPointTimeLimit = 60.0;

struct SweepOptions {
  unsigned threads = 0;  // 0: std::thread::hardware_concurrency()
  TaskSource next_task;  // empty: every task, in order
  // Called once per finished row, in completion order. An exception thrown here stops
  // the sweep (no new points start) and is rethrown by run_sweep.
  std::function<void(const Row&)> on_row;
  // Called after on_row with the number of rows done so far and the number of tasks.
  std::function<void(std::size_t done, std::size_t total)> on_progress;
  // When set to true, no new point starts, and the points already running end at their
  // solver's next look at the clock and are dropped (a resumed sweep solves them again).
  // run_sweep then returns the rows it has (fewer than the tasks).
  const std::atomic<bool>* cancel = nullptr;
  // Wall seconds a point may take when its run sets no Settings::time_limit of its own:
  // one point that never ends must not hold a whole sweep. Past it the row has status
  // time-limit and the sweep goes on. 0: no limit.
  double point_time_limit = kPointTimeLimit;
};

// Rows sorted by run, then point: one per task run (every task unless next_task says
// otherwise or the sweep was cancelled). Row::run is the index into `runs`.
std::vector<Row> run_sweep(std::span<const Case> cases, std::span<const SweepRun> runs,
                           const SweepOptions& options = {});
// A sweep of one run.
std::vector<Row> run_sweep(std::span<const Case> cases, const SolverInfo& solver, const Settings& settings,
                           const SweepOptions& options = {});

}  // namespace pb
