#include "app/workprecision_command.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "app/errors.hpp"
#include "app/output_files.hpp"
#include "app/sweep_watch.hpp"
#include "cases/case_set.hpp"
#include "sweep/workprecision.hpp"

namespace pb::app {

namespace {

constexpr int kInterrupted = 130;

void write_table(std::ostream& out, const WorkPrecision& wp) {
  out << work_precision_csv_header() << '\n';
  for (const WorkPrecisionRow& row : wp.table) out << work_precision_csv_line(row) << '\n';
}

}  // namespace

CLI::App* add_workprecision_command(CLI::App& app, WorkPrecisionFlags& flags) {
  CLI::App* command = app.add_subcommand(
      "workprecision", "Relative Pi1 error against CPU time per run, per family and solver setting");
  command->add_option("CASESET", flags.case_set, "Case-set file (TOML, see cases/README.md)")->required();
  command->add_option("--settings", flags.settings, "Settings-list file (TOML, see cases/settings/)")->required();
  command->add_option("--out", flags.out, "Write the summary CSV to this file (default: stdout)");
  command->add_option("--points", flags.points, "Also write every run's row (spectrum columns) to this file");
  command->add_option("--threads", flags.threads, "Worker threads (default: all cores)");
  return command;
}

int workprecision_command(const CLI::App& command, const WorkPrecisionFlags& flags) {
  const CaseSet set = load_case_set(flags.case_set);
  if (set.cases.empty()) throw BadInput(flags.case_set + ": no cases");
  SettingsList list;
  try {
    list = load_settings_list(flags.settings);
  } catch (const SettingsListError& e) {
    throw BadInput(e.what());
  }
  if (command.count("--threads") && flags.threads == 0) throw BadInput("--threads: must be >= 1");
  if (!flags.out.empty()) check_output_target(flags.out, "--out");
  if (!flags.points.empty()) check_output_target(flags.points, "--points");

  const std::size_t total = set.cases.size() * (list.runs.size() + 1);
  SweepWatch watch(total, ::isatty(STDERR_FILENO) == 1, [] { std::_Exit(kInterrupted); });
  SweepOptions options;
  options.threads = flags.threads;
  options.cancel = &watch.cancel();
  options.on_progress = [&](std::size_t done, std::size_t) { watch.set_done(done); };
  const WorkPrecision wp = run_work_precision(set.cases, list, options);
  watch.finish();
  if (!wp.complete) {
    std::fprintf(stderr, "poundbench: interrupted; nothing was written\n");
    return kInterrupted;
  }

  if (!flags.points.empty()) {
    write_atomically(flags.points, [&](std::ostream& out) {
      write_csv(out, wp.reference);
      for (const Row& row : wp.points) out << csv_line(row) << '\n';
    });
  }
  if (!flags.out.empty()) {
    write_atomically(flags.out, [&](std::ostream& out) { write_table(out, wp); });
  } else {
    write_table(std::cout, wp);
  }
  return 0;
}

}  // namespace pb::app
