#pragma once
// `poundbench workprecision CASESET --settings LIST`: every case through the reference and
// through every setting of a settings list (studies/settings_list.hpp); one CSV row per
// (family, solver, variant, setting) with the median, 95th percentile and max relative
// Pi1 error, the failed runs, and the median and mean CPU time per run. --points also
// writes every run's row (the columns of `spectrum`), reference first. Finished runs go to
// a partial file, from which a rerun resumes (output/resumable_sweep.hpp).
//
// `poundbench workprecision --settings LIST <run's case flags>`: the study of the one case
// the flags describe (in Pi terms or physical units, as `run` takes it; family "case"), the
// engineer's question of issue 35: which setting meets a target error, at what cost.

#include <limits>

#include <CLI/CLI.hpp>

#include "sweep/processes.hpp"
#include "app/study_run.hpp"
#include "frontend/case_flags.hpp"

namespace pb::app {

struct WorkPrecisionFlags : StudyFlags {
  double max_error = std::numeric_limits<double>::quiet_NaN();      // --max-error: NaN when not given
  double max_error_p95 = std::numeric_limits<double>::quiet_NaN();  // --max-error-p95: NaN when not given
  CaseFlags case_flags;  // the case, without CASESET
  std::vector<const CLI::Option*> case_options;  // their options, to tell whether any was given
};

CLI::App* add_workprecision_command(CLI::App& app, WorkPrecisionFlags& flags);
// Exit code: 0 done, 1 with --check when a run did not finish ok or a setting's err_median
// is above --max-error or its err_p95 above --max-error-p95 (the outputs are written all the
// same), 130 interrupted (partial file kept).
int workprecision_command(const CLI::App& command, const WorkPrecisionFlags& flags, const Processes& processes);

}  // namespace pb::app
