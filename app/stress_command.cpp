#include "app/stress_command.hpp"

#include <iostream>
#include <stdexcept>

#include "app/check_report.hpp"
#include "output/output_files.hpp"
#include "output/resumable_sweep.hpp"
#include "frontend/errors.hpp"
#include "studies/stress.hpp"

namespace pb::app {

namespace {

// --check: a verdict per row, failing with the checks it failed.
std::vector<Verdict> verdicts(const Stress& st) {
  std::vector<Verdict> out;
  for (const StressRow& row : st.table)
    out.push_back({"stress", row_label(row), row.passed() ? "" : "failed " + row.failed_checks()});
  return out;
}

}  // namespace

CLI::App* add_stress_command(CLI::App& app, StressFlags& flags) {
  return add_study_command(
      app, flags, "stress", "Checks (finite, energy, gap, restitution, accuracy) per family and solver setting",
      "Also write every run's row (spectrum columns, pi1_error)",
      "Exit 1 when any check of any row fails (after writing the outputs), naming each failing row on stderr");
}

int stress_command(const CLI::App& command, const StressFlags& flags, const Processes& processes) {
  Study study = run_study(command, flags, "stress", {.monitor = true}, processes);
  if (!study.rows) return kInterrupted;
  if (!processes.leader()) return 0;
  const Stress st =
      stress_of(study.set.cases, study.list, work_precision_of(study.set.cases, study.list, std::move(*study.rows)));

  std::size_t failed_runs = 0, failed_rows = 0;
  for (const std::vector<Row>* rows : {&st.runs.reference, &st.runs.points})
    for (const Row& r : *rows) failed_runs += r.result.status != Status::ok ? 1 : 0;
  for (const StressRow& row : st.table) failed_rows += row.ok < row.runs ? 1 : 0;
  write_study(
      flags, study, [&](std::ostream& out) { write_stress_points(out, st); },
      [&](std::ostream& out) { write_stress_table(out, st); },
      failed_runs, failed_rows);
  return flags.check ? report_check("stress", verdicts(st), "rows", flags.junit) : 0;
}

}  // namespace pb::app
