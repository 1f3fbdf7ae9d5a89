#pragma once
// A work-precision study: every case through the reference and through every setting of
// a settings list, summarised per (family, solver, variant, setting) as error against
// CPU time per run.

#include <span>
#include <string>
#include <vector>

#include "cases/case.hpp"
#include "sweep/settings_list.hpp"
#include "sweep/stats.hpp"
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

// options.on_progress receives the points done over the whole study.
WorkPrecision run_work_precision(std::span<const Case> cases, const SettingsList& list, const SweepOptions& options);

std::string work_precision_csv_header();
std::string work_precision_csv_line(const WorkPrecisionRow& row);

}  // namespace pb
