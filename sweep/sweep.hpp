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
#include <string>
#include <vector>

#include "cases/case.hpp"
#include "cases/case_list.hpp"
#include "kit/solver.hpp"
#include "kit/verdict.hpp"
#include "rows/row.hpp"
#include "sweep/no_contact_cache.hpp"

namespace pb {

// How a run is timed. Every solver the same way: solver.solve alone, on the thread's CPU clock
// (plus Result::child_cpu_seconds, the CPU of a program the solver ran), the clocks' own cost
// taken off (sweep/stopwatch.hpp), with Settings::monitor off (the monitor's bookkeeping is
// not the scheme's cost: it made Moreau-Jean 2.4 times slower), repeated up to `repetitions`
// times. A point stops repeating once its timed solves have spent kRepetitionBudget CPU
// seconds together (it is solved at least once): on the main job's work-precision study, five
// repetitions of every run would cost 5 times one timing, and this rule keeps it to 1.6 times
// (measured: docs/cli.md), while every run faster than 2 ms, most of them, gets its 5. The row
// holds the median, the fastest and the slowest (rows/row.hpp).
//
// The monitor's measurements (energy_excess, the restitution range, gap_rate_max, which the
// stress checks judge) come from one more solve, untimed, with the monitor on, when the
// run's Settings::monitor asks for them; the reference keeps its own checks whatever the
// monitor says, so it has no such pass, and neither has a timed solve cut short by its
// time limit (it would cost as much again). The monitor must not change the result: a
// monitored solve whose status or Pi1 differs, bit for bit, from the timed ones fails the
// row, and so does a timed repetition that differs from the first (a solver that is not
// deterministic). A later repetition cut short by the time limit or the stop flag is not
// a timing of the same run: the repetitions end there without it; a monitored solve cut
// short leaves the row unmeasured, its message saying so.
// A solver solved in one pass (SolverInfo::one_pass: the external solver, whose program a second
// pass would run twice per point) has no monitored pass: its timed solve carries the run's
// Settings::monitor, and its own measurements are the row's.
inline constexpr int kMaxRepetitions = 1000;
inline constexpr double kRepetitionBudget = 0.01;  // CPU seconds per point, over its repetitions

// The error estimate of a fixed-step run (Result::error_estimate) and the target its verdict
// holds it to (kit/verdict.hpp). on: run_point solves the case once more, untimed, at twice
// the run's step (Settings::wh = 2 w_max h, without a record's step rule: the companion's step is
// exactly 2h), for a solver with a SolverInfo::step_order whose run had a fixed step; that costs
// about half a solve more. A companion that does not end ok makes the run unresolved (a doubt);
// one the solver's check refuses, or that the time limit cuts short, leaves the run without an
// estimate (not judged). Its time is not the row's: the row times the run at h alone.
// `run` estimates by default; a sweep with --estimate-error.
struct ErrorEstimate {
  bool on = false;
  double target_error = kTargetError;
};

// Solves one case: builds the System, times solver.solve alone (as above, 1 <= repetitions
// <= kMaxRepetitions), adds the monitor's measurements when settings.monitor asks and the
// no-contact Pi1 (from `no_contact` when given: a sweep's cache, sweep/no_contact_cache.hpp).
// Never throws for a bad case or a throwing solver: the row then has Status::failed and the
// reason in its message.
// monitor_timed: the timed solves keep settings.monitor as it is and there is no monitored
// pass. `run` monitors its one solve so: the verdict then judges every criterion at the cost of
// one solve (the monitor adds 30 % to 44 % to a Moreau-Jean step), where a second pass doubled it.
// The verdict (kit/verdict.hpp) is not judged (resolved empty) where it cannot be true
// for want of a measurement: with settings.monitor off (but the reference's own checks), or
// for a fixed-step run with a step_order whose estimate was not made (`estimate` off, or none
// made), unless a criterion it did measure fails.
// described: solver.describe(settings), where the caller has made it (a sweep, once per run).
Row run_point(const Case& c, std::size_t point, const SolverInfo& solver, const Settings& settings,
              int repetitions = 1, NoContactCache* no_contact = nullptr, bool monitor_timed = false,
              const ErrorEstimate& estimate = {}, const std::string* described = nullptr);

// Every body's peak with contact (Row::peaks), by the same solver and settings: each other body
// as the reported one (System::ref) in one more solve, the motion being the same; body 0's is
// the row's Pi1. For `run` (and poundbench.run) alone: a sweep would pay a solve per body. Not for
// a chain or the wall (one body), a row that did not end ok, a solver run once a point
// (SolverInfo::one_pass: the external solver), nor under a time limit (it is the whole run's); a
// solve that does not end ok leaves that body's peak NaN.
void add_body_peaks(Row& row, const SolverInfo& solver, const Settings& settings);

// One solver with its settings, run over every case of a sweep. settings.monitor: the rows
// carry the monitor's measurements, from one untimed pass more (run_point), or, with
// monitor_timed, from the timed solves themselves (their cost then includes the monitor's).
struct SweepRun {
  const SolverInfo* solver = nullptr;
  Settings settings;
  int repetitions = 1;         // timed solves per point, at most (run_point)
  bool monitor_timed = false;  // run_point's monitor_timed
  ErrorEstimate estimate{};    // run_point's estimate (--estimate-error, --target-error)
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
  // Called once per finished row before on_row by the worker that finished it, outside the
  // lock that serialises the other callbacks: from several threads at once. Work that needs
  // no order (the partial file's line of the row: output/partial_writer.hpp) goes here, so that
  // the workers do it side by side and not one at a time. An exception thrown here stops
  // the sweep as one from on_row does.
  std::function<void(const Row&)> on_finished;
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
  // false: run_sweep keeps no row (it returns none): on_row is where they go. A sweep of a
  // million points held 1.5 KB a point until its end (issue 36); `spectrum` streams its rows
  // to the partial file and builds its output from there (output/partial_output.hpp).
  bool keep_rows = true;
  // Where a run is the external solver's persistent mode and the workers are no more than the
  // cores: worker k and its program on core k (sweep/worker_cores.hpp says why). Off for an
  // MPI job's ranks, which share a node's cores.
  bool pin_persistent = true;
};

// Rows sorted by run, then point: one per task run (every task unless next_task says
// otherwise or the sweep was cancelled). Row::run is the index into `runs`.
std::vector<Row> run_sweep(const CaseList& cases, std::span<const SweepRun> runs,
                           const SweepOptions& options = {});
// A sweep of one run.
std::vector<Row> run_sweep(const CaseList& cases, const SolverInfo& solver, const Settings& settings,
                           const SweepOptions& options = {});

}  // namespace pb
