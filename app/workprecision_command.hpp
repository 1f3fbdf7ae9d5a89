#pragma once
// `poundbench workprecision CASESET --settings LIST`: every case through the reference and
// through every setting of a settings list (sweep/settings_list.hpp); one CSV row per
// (family, solver, variant, setting) with the median, 95th percentile and max relative
// Pi1 error, the failed runs, and the median and mean CPU time per run. --points also
// writes every run's row (the columns of `spectrum`), reference first.

#include <string>

#include <CLI/CLI.hpp>

namespace pb::app {

struct WorkPrecisionFlags {
  std::string case_set;
  std::string settings;
  std::string out;     // empty: stdout
  std::string points;  // empty: not written
  unsigned threads = 0;
};

CLI::App* add_workprecision_command(CLI::App& app, WorkPrecisionFlags& flags);
// Exit code: 0 done, 130 interrupted (nothing written).
int workprecision_command(const CLI::App& command, const WorkPrecisionFlags& flags);

}  // namespace pb::app
