#include "app/workprecision_command.hpp"

#include <iostream>
#include <stdexcept>

#include "app/errors.hpp"
#include "app/output_files.hpp"
#include "app/resumable_sweep.hpp"
#include "studies/workprecision.hpp"

namespace pb::app {

namespace {

void write_table(std::ostream& out, const WorkPrecision& wp) {
  out << work_precision_csv_header() << '\n';
  for (const WorkPrecisionRow& row : wp.table) out << work_precision_csv_line(row) << '\n';
}

}  // namespace

CLI::App* add_workprecision_command(CLI::App& app, WorkPrecisionFlags& flags) {
  return add_study_command(app, flags, "workprecision",
                           "Relative Pi1 error against CPU time per run, per family and solver setting",
                           "Also write every run's row (spectrum columns) to this file");
}

int workprecision_command(const CLI::App& command, const WorkPrecisionFlags& flags, const Processes& processes) {
  Study study = run_study(command, flags, "workprecision", processes);
  if (!study.rows) return kInterrupted;
  if (!processes.leader()) return 0;
  const WorkPrecision wp = work_precision_of(study.set.cases, study.list, std::move(*study.rows));

  write_study(
      flags, study,
      [&](std::ostream& out) {
        write_csv(out, wp.reference);
        for (const Row& row : wp.points) out << csv_line(row) << '\n';
      },
      [&](std::ostream& out) { write_table(out, wp); });
  return 0;
}

}  // namespace pb::app
