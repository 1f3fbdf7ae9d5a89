#pragma once
// `poundbench spectrum CASESET`: every case of a case-set file through one solver, one CSV
// row per case in point order (columns: rows/row.hpp).
//
// Rows are appended, flushed, to a partial file as they complete (completion order), so an
// interrupt or a crash loses only the points that were running, and a rerun with the same
// output resumes (output/resumable_sweep.hpp). The final output appears only when every point
// is done: --out is written as FILE.tmp and renamed, stdout gets the rows at the end, and
// the partial file is removed. Under mpirun the points are shared among the ranks.

#include <string>

#include <CLI/CLI.hpp>

#include "frontend/solver_flags.hpp"
#include "sweep/processes.hpp"

namespace pb::app {

struct SpectrumFlags {
  std::string case_set;
  std::string out;  // empty: stdout
  unsigned threads = 0;
  int repetitions = 1;  // timed solves per point, at most (sweep/sweep.hpp)
  bool check = false;   // exit 1 when a point did not finish ok (after writing the output)
  std::string junit;    // --junit: --check's verdicts, a testcase per family (app/check_report.hpp)
  SolverFlags solver_flags;
  ErrorEstimate estimate{};  // --estimate-error, --target-error
};

CLI::App* add_spectrum_command(CLI::App& app, SpectrumFlags& flags);
// Exit code: 0 done (whatever the points' statuses, unless --check), 1 with --check when a
// point did not finish ok (the output is written all the same), 130 interrupted (partial
// file kept).
int spectrum_command(const CLI::App& command, const SpectrumFlags& flags, const Processes& processes);

}  // namespace pb::app
