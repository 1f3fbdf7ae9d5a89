#include "app/study_run.hpp"

#include <iostream>
#include <streambuf>

#include "app/check_report.hpp"
#include "output/output_files.hpp"
#include "output/resumable_sweep.hpp"
#include "output/sweep_watch.hpp"
#include "frontend/errors.hpp"
#include "frontend/solver_flags.hpp"
#include "studies/workprecision.hpp"

namespace pb::app {

namespace {

// Passes what is written on to another stream buffer, counting the CSV records: the line
// ends outside quoted fields (a doubled quote toggles twice, as the reader reads it).
class RecordCount : public std::streambuf {
 public:
  explicit RecordCount(std::streambuf* to) : to_(to) {}
  std::size_t records() const { return records_; }

 protected:
  int_type overflow(int_type ch) override {
    if (traits_type::eq_int_type(ch, traits_type::eof())) return traits_type::not_eof(ch);
    const char c = traits_type::to_char_type(ch);
    if (c == '"') quoted_ = !quoted_;
    if (c == '\n' && !quoted_) ++records_;
    return to_->sputc(c);
  }
  int sync() override { return to_->pubsync(); }

 private:
  std::streambuf* to_;
  std::size_t records_ = 0;
  bool quoted_ = false;
};

// `write`, which writes a header and rows, with the rows it wrote counted into `rows`.
std::function<void(std::ostream&)> counted(const std::function<void(std::ostream&)>& write, std::size_t& rows) {
  return [&write, &rows](std::ostream& out) {
    RecordCount count(out.rdbuf());
    std::ostream counting(&count);
    write(counting);
    counting.flush();
    if (!counting) out.setstate(std::ios::badbit);
    rows = count.records() > 0 ? count.records() - 1 : 0;
  };
}

}  // namespace

void add_repetitions_flag(CLI::App& command, int& repetitions) {
  command
      .add_option("--repetitions", repetitions,
                  "Timed solves per point, at most: the row has their median, fastest and slowest (a point stops "
                  "repeating once its solves have spent 10 ms of CPU time)")
      ->check(CLI::Range(1, kMaxRepetitions))
      ->capture_default_str();
}

SettingsList read_settings_list(const std::string& file, bool say) {
  SettingsList list;
  try {
    list = load_settings_list(file);
  } catch (const SettingsListError& e) {
    throw BadInput(e.what());
  }
  if (say)
    for (const std::string& run : list.left_out)
      std::cerr << "poundbench: " << file << ": " << run << " is not in this build: skipped\n";
  return list;
}

CLI::App* add_study_command(CLI::App& app, StudyFlags& flags, std::string_view name, std::string_view summary,
                            std::string_view points_help, std::string_view check_help) {
  CLI::App* command = app.add_subcommand(std::string(name), std::string(summary));
  command->add_option("CASESET", flags.case_set, "Case-set file (TOML, see cases/README.md)");
  command->add_option("--settings", flags.settings, "Settings-list file (TOML, see cases/settings/)")->required();
  command->add_option("--out", flags.out, "Write the summary CSV to this file (default: stdout)");
  command->add_option("--points", flags.points, std::string(points_help));
  command->add_option("--threads", flags.threads, "Worker threads (default: all cores)");
  add_repetitions_flag(*command, flags.repetitions);
  add_estimate_flags(*command, flags.estimate, true);
  command->add_flag("--check", flags.check, std::string(check_help));
  add_junit_flag(*command, flags.junit, "summary row");
  return command;
}

Study run_study(const CLI::App& command, const StudyFlags& flags, std::string_view name, StudyOptions options,
                const Processes& processes, const std::function<CaseSet()>& case_from_flags) {
  options.repetitions = flags.repetitions;
  options.estimate = flags.estimate;
  Study study;
  std::vector<SweepRun> runs;
  EarlierRows earlier;
  study.partial = partial_file_name(flags.out, name);
  processes.agree([&] {
    if (!flags.case_set.empty())
      study.set = load_case_set(flags.case_set);
    else if (case_from_flags)
      study.set = case_from_flags();
    else
      throw BadInput("CASESET: required (the case-set file)");
    if (study.set.cases.empty()) throw BadInput(flags.case_set + ": no cases");
    study.list = read_settings_list(flags.settings, processes.leader());
    try {
      resolve_physical_settings(study.list, study.set.cases, flags.settings);
    } catch (const SettingsListError& e) {
      throw BadInput(e.what());
    }
    if (command.count("--threads") && flags.threads == 0) throw BadInput("--threads: must be >= 1");
    check_estimate_flags(command, flags.estimate, true);
    runs = study_runs(study.list, options);
    if (!processes.leader()) return;
    std::vector<NamedFile> inputs = record_files(study.set.cases);
    if (!flags.case_set.empty()) inputs.push_back({"CASESET", flags.case_set});
    inputs.push_back({"--settings", flags.settings});
    check_outputs_apart({{"--out", flags.out}, {"--points", flags.points}, {"--junit", flags.junit}}, inputs,
                        study.partial, lock_file_name(flags.out, name));
    if (!flags.out.empty()) check_sweep_output(flags.out, "--out");
    if (!flags.points.empty()) check_sweep_output(flags.points, "--points");
    check_junit_target(flags.junit, flags.check);
    study.lock = take_output_lock(flags.out, name, study.partial);
    earlier = read_earlier_rows(study.partial, study.set.cases, runs);
  }, exit_code_of);
  study.rows = run_resumable(name, processes, study.set.cases, runs, study.partial, study.lock, std::move(earlier),
                             flags.threads);
  return study;
}

void write_study(const StudyFlags& flags, const Study& study, const std::function<void(std::ostream&)>& points,
                 const std::function<void(std::ostream&)>& table, std::size_t failed_runs, std::size_t failed_rows) {
  std::size_t point_rows = 0, table_rows = 0;
  write_outputs(study.partial, [&] {
    if (!flags.points.empty()) write_atomically(flags.points, counted(points, point_rows));
    if (flags.out.empty())
      write_to_stdout(counted(table, table_rows));
    else
      write_atomically(flags.out, counted(table, table_rows));
  });
  if (!flags.points.empty())
    report_written(point_rows, flags.points, failed_runs ? failed_note(failed_runs, "runs", flags.check) : "");
  report_written(table_rows, flags.out,
                 failed_rows ? std::to_string(failed_rows) + " with runs that did not finish ok" : "");
}

}  // namespace pb::app
