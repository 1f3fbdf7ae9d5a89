#include "app/stress_command.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <stdexcept>

#include "app/errors.hpp"
#include "app/output_files.hpp"
#include "app/sweep_watch.hpp"
#include "cases/case_set.hpp"
#include "sweep/stability.hpp"

namespace pb::app {

namespace {

constexpr int kInterrupted = 130;

void write_table(std::ostream& out, const Stress& st) {
  out << stability_csv_header() << '\n';
  for (const StabilityRow& row : st.table) out << stability_csv_line(row) << '\n';
}

void write_points(std::ostream& out, const Stress& st) {
  out << stress_points_header() << '\n';
  const double none = std::numeric_limits<double>::quiet_NaN();
  for (const Row& row : st.runs.reference) out << stress_points_line(row, none) << '\n';
  for (const Row& row : st.runs.points) out << stress_points_line(row, pi1_error(row, st.truth[row.point])) << '\n';
}

}  // namespace

CLI::App* add_stress_command(CLI::App& app, StressFlags& flags) {
  CLI::App* command = app.add_subcommand(
      "stress", "Stability checks (finite, energy, gap, restitution) per family and solver setting");
  command->add_option("CASESET", flags.case_set, "Case-set file (TOML, see cases/README.md)")->required();
  command->add_option("--settings", flags.settings, "Settings-list file (TOML, see cases/settings/)")->required();
  command->add_option("--out", flags.out, "Write the summary CSV to this file (default: stdout)");
  command->add_option("--points", flags.points, "Also write every run's row (spectrum columns, pi1_error)");
  command->add_option("--threads", flags.threads, "Worker threads (default: all cores)");
  return command;
}

int stress_command(const CLI::App& command, const StressFlags& flags) {
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
  const Stress st = run_stress(set.cases, list, options);
  watch.finish();
  if (!st.complete) {
    std::fprintf(stderr, "poundbench: interrupted; nothing was written\n");
    return kInterrupted;
  }

  if (!flags.points.empty()) write_atomically(flags.points, [&](std::ostream& out) { write_points(out, st); });
  if (!flags.out.empty()) {
    write_atomically(flags.out, [&](std::ostream& out) { write_table(out, st); });
  } else {
    write_table(std::cout, st);
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("stdout: write failed");
  }
  return 0;
}

}  // namespace pb::app
