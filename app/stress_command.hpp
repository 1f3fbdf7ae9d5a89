#pragma once
// `poundbench stress CASESET --settings LIST`: every case through the reference (the truth)
// and through every setting of a settings list, then the stability checks of
// sweep/stability.hpp per (family, solver, variant, setting): one summary CSV row each,
// with pass or fail per check. --points also writes every run's row (the columns of
// `spectrum` plus pi1_error), the truth first.

#include <string>

#include <CLI/CLI.hpp>

namespace pb::app {

struct StressFlags {
  std::string case_set;
  std::string settings;
  std::string out;     // empty: stdout
  std::string points;  // empty: not written
  unsigned threads = 0;
};

CLI::App* add_stress_command(CLI::App& app, StressFlags& flags);
// Exit code: 0 done (whatever the checks say), 130 interrupted (nothing written).
int stress_command(const CLI::App& command, const StressFlags& flags);

}  // namespace pb::app
