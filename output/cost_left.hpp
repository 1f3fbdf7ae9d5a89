#pragma once
// What is left of a sweep in seconds, from the cost of what is left, run by run (a setting
// each), rather than from the count: a work-precision study's runs range from the reference
// and coarse steps to fine ones hundreds of times dearer, and a count's rate said "about 34 s
// left" at 10 s with about 3 min to go, a stress run "ETA 0:21" with 166 s left (issue 36).
//
// Each finished row's cost is the CPU its solves took (Row: cpu_seconds times repetitions).
// A run with finished rows costs their mean per point left; a run with none yet, the mean of
// a finished run of the same solver scaled by their steps per period (a time-stepper's cost
// goes with its number of steps; steps N, or 2 pi / wh), and failing that the mean of every
// finished row. The sum over what is left is turned into seconds by the sweep's own ratio of
// elapsed wall time to the cost it has finished, which carries the threads, the processes and
// what a point costs beside its timed solves.

#include <cstddef>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "rows/row.hpp"
#include "sweep/sweep.hpp"

namespace pb::app {

class CostLeft {
 public:
  // `todo`: the tasks (run * cases + point) the sweep will solve.
  CostLeft(std::span<const SweepRun> runs, std::size_t cases, std::span<const std::size_t> todo);

  // A finished row (any thread).
  void add(const Row& row);
  // Seconds left after `elapsed` seconds of this sweep; nullopt until a row has finished.
  std::optional<double> seconds_left(double elapsed) const;

 private:
  struct Run {
    const SolverInfo* solver = nullptr;
    double steps = 0.0;  // steps per shortest period, 0 where the settings do not say
    std::size_t left = 0, done = 0;
    double cost = 0.0;   // CPU seconds of its finished rows
  };
  mutable std::mutex mutex_;
  std::vector<Run> runs_;
  std::size_t cases_;
  double cost_ = 0.0;  // of every finished row
  std::size_t done_ = 0;
};

}  // namespace pb::app
