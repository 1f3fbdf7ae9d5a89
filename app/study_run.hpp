#pragma once
// What `workprecision` and `stress` share: a case set and a settings list, checked on every
// process, the output files checked on the leader, and the study (the truth and every
// setting, studies/workprecision.hpp) run as one resumable sweep (output/resumable_sweep.hpp).

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "output/output_lock.hpp"
#include "sweep/processes.hpp"
#include "cases/case_set.hpp"
#include "rows/row.hpp"
#include "studies/settings_list.hpp"
#include "studies/workprecision.hpp"

namespace pb::app {

struct StudyFlags {
  std::string case_set;
  std::string settings;
  std::string out;     // empty: stdout
  std::string points;  // empty: not written
  unsigned threads = 0;
  int repetitions = kStudyRepetitions;
  bool check = false;  // exit 1 when a row fails (after writing the outputs)
  std::string junit;   // --junit: --check's verdicts as JUnit XML (app/check_report.hpp)
  ErrorEstimate estimate{};  // --estimate-error, --target-error: the list's runs' (StudyOptions)
};

// --repetitions R: timed solves per point, at most (sweep/sweep.hpp), from 1 to
// kMaxRepetitions; `spectrum` has it too.
void add_repetitions_flag(CLI::App& command, int& repetitions);

// A command's settings list (`workprecision`, `stress`, `baseline`): its errors as BadInput,
// and, when `say` (the leader), each run of an engine this build left out named on stderr.
SettingsList read_settings_list(const std::string& file, bool say);

// CASESET, --settings, --out, --points, --threads, --repetitions, --estimate-error, --target-error,
// --check with `check_help`, --junit.
CLI::App* add_study_command(CLI::App& app, StudyFlags& flags, std::string_view name, std::string_view summary,
                            std::string_view points_help, std::string_view check_help);

struct Study {
  CaseSet set;
  SettingsList list;
  std::string partial;                    // its partial file
  OutputLock lock;                        // of the outputs, on the leader, while the Study lives
  std::optional<std::vector<Row>> rows;   // on the leader, every row; nullopt: interrupted
};

// `name` names the partial file when the output is stdout; `options` says what the study
// asks of its runs (StudyOptions; its repetitions come from the flags).
// Without CASESET, the cases are `case_from_flags()`'s (`workprecision`'s one case given by
// run's case flags), or none given is an error. A list's runs in physical units are mapped
// to their Pi forms over the cases (studies/physical_settings.hpp).
Study run_study(const CLI::App& command, const StudyFlags& flags, std::string_view name, StudyOptions options,
                const Processes& processes, const std::function<CaseSet()>& case_from_flags = {});

// Writes a finished study's outputs, whole or not at all: the rows of every run to
// --points when asked, then the summary table to --out or stdout; the partial file goes
// once both are written. The closing line of each file counts what failed in it, where
// anything did: the runs that did not finish ok, the summary rows with such runs.
void write_study(const StudyFlags& flags, const Study& study, const std::function<void(std::ostream&)>& points,
                 const std::function<void(std::ostream&)>& table, std::size_t failed_runs, std::size_t failed_rows);

// A summary row as --check names it: family, solver, variant (when given) and settings.
template <typename SummaryRow>
std::string row_label(const SummaryRow& row) {
  return row.family + " " + row.solver + (row.variant.empty() ? "" : " " + row.variant) + " " + row.settings;
}

}  // namespace pb::app
