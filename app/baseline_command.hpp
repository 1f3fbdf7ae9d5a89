#pragma once
// `poundbench baseline` and `poundbench compare`: the accuracy regression baselines
// (studies/baseline.hpp) from the command line.
//
//   baseline CASESET [--settings LIST] --out FILE   store the rows of a case set through the
//                                                   reference and every setting of LIST
//   baseline --check FILE...                        rerun what each file says made it and
//                                                   compare, each solver within its tolerance
//   baseline --update FILE...                       rerun and store again (a deliberate
//                                                   re-baseline)
//   compare ROWS --baseline FILE --tolerance X      another program's rows (at least the
//                                                   columns of rows/minimal_rows.hpp)
//                                                   against the stored reference; a row
//                                                   with no stored case fails unless
//                                                   --allow-unmatched
//   --junit FILE (with --check, and on compare)     the verdicts as JUnit XML
//
// Exit codes: 0 all within tolerance (or written), 1 a check failed, 2 bad input, 130
// interrupted (nothing written).

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace pb::app {

struct BaselineFlags {
  std::string case_set;  // write mode
  std::string settings;  // write mode; empty: the reference alone
  std::string out;       // write mode
  std::vector<std::string> check, update;
  unsigned threads = 0;
  std::string junit;  // --junit with --check (app/check_report.hpp)
};

struct CompareFlags {
  std::string rows;
  std::string baseline;
  double tolerance = 0.0;
  bool same_setting = false;
  bool allow_unmatched = false;  // a row with no stored case does not fail its family
  std::string junit;
};

CLI::App* add_baseline_command(CLI::App& app, BaselineFlags& flags);
int baseline_command(const CLI::App& command, const BaselineFlags& flags);

CLI::App* add_compare_command(CLI::App& app, CompareFlags& flags);
int compare_command(const CLI::App& command, const CompareFlags& flags);

}  // namespace pb::app
