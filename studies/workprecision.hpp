#pragma once
// A work-precision study: every case through the reference and through every setting of
// a settings list, summarised per (family, solver, variant, setting) as error against
// CPU time per run.
//
// A study is one sweep (sweep/sweep.hpp) whose runs are the truth and then the list's
// settings, so its tasks are shared out together: no thread or MPI rank waits for the
// slowest point of one setting before starting the next.

#include <span>
#include <string>
#include <vector>

#include "cases/case.hpp"
#include "studies/settings_list.hpp"
#include "studies/stats.hpp"
#include "sweep/sweep.hpp"

namespace pb {

struct WorkPrecisionRow {
  std::string family;
  std::string solver;
  std::string variant;
  std::string settings;  // SolverInfo::describe
  Summary summary;
};

struct WorkPrecision {
  std::vector<Row> reference;          // the truth, one row per case
  std::vector<Row> points;             // every run, setting after setting: run k of the list
                                       // is points[k n, (k+1) n), in point order (n cases)
  std::vector<WorkPrecisionRow> table;  // per family (in case order), then per setting
  bool complete = false;                // false: cancelled before the end
};

// The study's runs: the truth (the reference at the list's tolerance scale and time
// limit), then the list's runs in their order.
std::vector<SweepRun> study_runs(const SettingsList& list);

// The study from its rows: one per task, sorted by run then point, as run_sweep returns
// them over study_runs(list). Fewer rows than tasks: not complete, no table.
WorkPrecision work_precision_of(std::span<const Case> cases, const SettingsList& list, std::vector<Row> rows);

// run_sweep over study_runs(list), then work_precision_of.
WorkPrecision run_work_precision(std::span<const Case> cases, const SettingsList& list, const SweepOptions& options);

std::string work_precision_csv_header();
std::string work_precision_csv_line(const WorkPrecisionRow& row);

}  // namespace pb
