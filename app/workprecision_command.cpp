#include "app/workprecision_command.hpp"

#include <cmath>
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

// --check: every row with a run that did not finish ok or, with --max-error, too large an error.
std::vector<std::string> failures(const WorkPrecision& wp, double max_error) {
  std::vector<std::string> out;
  for (const WorkPrecisionRow& row : wp.table)
    if (const std::string problem = work_precision_problem(row, max_error); !problem.empty())
      out.push_back(row_label(row) + ": " + problem);
  return out;
}

}  // namespace

CLI::App* add_workprecision_command(CLI::App& app, WorkPrecisionFlags& flags) {
  CLI::App* command = add_study_command(
      app, flags, "workprecision", "Relative Pi1 error against CPU time per run, per family and solver setting",
      "Also write every run's row (spectrum columns) to this file",
      "Exit 1 when a run did not finish ok, or a setting's err_median is above --max-error (after writing the "
      "outputs), naming each failing row on stderr");
  command->add_option("--max-error", flags.max_error,
                      "With --check: the largest err_median a setting may have in a family (relative)");
  return command;
}

int workprecision_command(const CLI::App& command, const WorkPrecisionFlags& flags, const Processes& processes) {
  processes.agree([&] {
    if (!command.count("--max-error")) return;
    if (!(flags.max_error >= 0.0 && std::isfinite(flags.max_error)))
      throw BadInput("--max-error: must be a finite number >= 0");
    if (!flags.check) throw BadInput("--max-error: needs --check");
  }, exit_code_of);
  Study study = run_study(command, flags, "workprecision", {.model_references = true}, processes);
  if (!study.rows) return kInterrupted;
  if (!processes.leader()) return 0;
  const WorkPrecision wp = work_precision_of(study.set.cases, study.list, std::move(*study.rows), true);

  write_study(
      flags, study,
      [&](std::ostream& out) {
        write_csv(out, wp.reference);
        for (const Row& row : wp.points) out << csv_line(row) << '\n';
      },
      [&](std::ostream& out) { write_table(out, wp); });
  return flags.check ? report_check("workprecision", failures(wp, flags.max_error), wp.table.size()) : 0;
}

}  // namespace pb::app
