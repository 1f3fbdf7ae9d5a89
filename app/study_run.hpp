#pragma once
// What `workprecision` and `stress` share: a case set and a settings list, checked on every
// process, the output files checked on the leader, and the study (the truth and every
// setting, studies/workprecision.hpp) run as one resumable sweep (app/resumable_sweep.hpp).

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/output_lock.hpp"
#include "sweep/processes.hpp"
#include "cases/case_set.hpp"
#include "rows/row.hpp"
#include "studies/settings_list.hpp"

namespace pb::app {

struct StudyFlags {
  std::string case_set;
  std::string settings;
  std::string out;     // empty: stdout
  std::string points;  // empty: not written
  unsigned threads = 0;
};

// CASESET, --settings, --out, --points, --threads.
CLI::App* add_study_command(CLI::App& app, StudyFlags& flags, std::string_view name, std::string_view summary,
                            std::string_view points_help);

struct Study {
  CaseSet set;
  SettingsList list;
  std::string partial;                    // its partial file
  OutputLock lock;                        // of the outputs, on the leader, while the Study lives
  std::optional<std::vector<Row>> rows;   // on the leader, every row; nullopt: interrupted
};

// `name` names the partial file when the output is stdout.
Study run_study(const CLI::App& command, const StudyFlags& flags, std::string_view name, const Processes& processes);

// Writes a finished study's outputs, whole or not at all: the rows of every run to
// --points when asked, then the summary table to --out or stdout; the partial file goes
// once both are written.
void write_study(const StudyFlags& flags, const Study& study, const std::function<void(std::ostream&)>& points,
                 const std::function<void(std::ostream&)>& table);

}  // namespace pb::app
