#pragma once
// `poundbench stress CASESET --settings LIST`: every case through the reference (the truth)
// and through every setting of a settings list, then the checks of studies/stress.hpp
// (stability and accuracy) per (family, solver, variant, setting): one summary CSV row
// each, with pass or fail per check. --points also writes every run's row (the columns of
// `spectrum` plus pi1_error), the truth first. Finished runs go to a partial file, from
// which a rerun resumes (output/resumable_sweep.hpp).

#include <CLI/CLI.hpp>

#include "sweep/processes.hpp"
#include "app/study_run.hpp"

namespace pb::app {

using StressFlags = StudyFlags;

CLI::App* add_stress_command(CLI::App& app, StressFlags& flags);
// Exit code: 0 done (whatever the checks say, unless --check), 1 with --check when a check
// of a row failed (the outputs are written all the same), 130 interrupted (partial file kept).
int stress_command(const CLI::App& command, const StressFlags& flags, const Processes& processes);

}  // namespace pb::app
