#pragma once
// A work-precision study: every case through the reference and through every setting of
// a settings list, summarised per (family, solver, variant, setting) as error against
// CPU time per run.
//
// A study is one sweep (sweep/sweep.hpp) whose runs are the truth and then the list's
// settings, so its tasks are shared out together: no thread or MPI rank waits for the
// slowest point of one setting before starting the next.

#include <limits>
#include <span>
#include <ostream>
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
  // Against the reference of the setting's own model (SolverInfo::model_reference), where it
  // has one: its integration error alone (summary's error is the model's and the integration's
  // together, against the rigid reference). Empty model_reference: none.
  std::string model_reference;  // "solver settings" of that reference
  Summary integration;
  PhysicalSetting physical;  // the setting's step (s) and stiffness (N/m) as the list gave them
};

struct WorkPrecision {
  std::vector<Row> reference;          // the truth, one row per case
  std::vector<Row> points;             // every run, setting after setting: run k of the list
                                       // is points[k n, (k+1) n), in point order (n cases)
  std::vector<WorkPrecisionRow> table;  // per family (in case order), then per setting
  bool complete = false;                // false: cancelled before the end
};

// The timed repetitions per point of a study's runs, at most (sweep/sweep.hpp's rule).
inline constexpr int kStudyRepetitions = 5;

// What a study asks of its runs beyond the list's settings.
struct StudyOptions {
  int repetitions = kStudyRepetitions;  // timed solves per point, at most (run_point)
  // true: each run's Settings::monitor is the list's `monitor` (on unless switched off), so
  // its rows carry the monitor's measurements (the stress checks judge them), measured by the
  // timed solves themselves: their cost includes the monitor's, and a point is solved once per
  // repetition, where an untimed monitored pass more was 44 % of the stress study's CPU time
  // at one repetition (the same verdicts in every row).
  // false: off for every run: a work-precision study judges none of them.
  bool monitor = false;
  // true: the list's runs are followed by the references of their own models
  // (model_reference_runs), and the table measures each run against its model's too.
  bool model_references = false;
  // The list's runs' error estimates (sweep/sweep.hpp, ErrorEstimate: --estimate-error); not the
  // truth's or the model references', which have no fixed step.
  ErrorEstimate estimate{};
};

// The references of the list's runs' own models (SolverInfo::model_reference) that the list
// does not hold, each once, in the order of the runs that ask for them.
std::vector<SweepRun> model_reference_runs(const SettingsList& list);

// The study's runs: the truth (the reference at the list's tolerance scale and time
// limit), then the list's runs in their order, then (StudyOptions::model_references) the
// references of their models.
std::vector<SweepRun> study_runs(const SettingsList& list, const StudyOptions& study = {});

// The study from its rows: one per task, sorted by run then point, as run_sweep returns
// them over study_runs(list, study) with the same model_references. Fewer rows than tasks:
// not complete, no table.
WorkPrecision work_precision_of(std::span<const Case> cases, const SettingsList& list, std::vector<Row> rows,
                                bool model_references = false);

// run_sweep over study_runs(list, study), then work_precision_of.
WorkPrecision run_work_precision(std::span<const Case> cases, const SettingsList& list, const SweepOptions& options,
                                 const StudyOptions& study = {});

std::string work_precision_csv_header();
std::string work_precision_csv_line(const WorkPrecisionRow& row);
// The study's summary table (`workprecision --out`), and every run's row, the truth first
// (`--points`): what the command and the Python module write.
void write_work_precision_table(std::ostream& out, const WorkPrecision& wp);
void write_work_precision_points(std::ostream& out, const WorkPrecision& wp);

// What `workprecision --check` fails a row for, "" when nothing: a run that did not finish
// ok (a failed count), one that did not resolve what it solved (an unresolved count), or,
// when max_error (max_error_p95) is not NaN, an err_median (err_p95) above it.
std::string work_precision_problem(const WorkPrecisionRow& row, double max_error,
                                   double max_error_p95 = std::numeric_limits<double>::quiet_NaN());

}  // namespace pb
