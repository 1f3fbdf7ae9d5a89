#include "app/spectrum_command.hpp"

#include <iostream>
#include <stdexcept>

#include "app/case_flags.hpp"
#include "app/errors.hpp"
#include "app/output_files.hpp"
#include "app/resumable_sweep.hpp"
#include "app/sweep_watch.hpp"
#include "app/study_run.hpp"
#include "cases/case_set.hpp"
#include "sweep/sweep.hpp"

namespace pb::app {

namespace {

// lines: each row's CSV line by point as the sweep wrote it to the partial file ("" for a
// row read back from it), so that no row is formatted twice.
void write_final(const SpectrumFlags& flags, const std::vector<Row>& rows, const std::vector<std::string>& lines) {
  const auto csv = [&](std::ostream& out) {
    out << csv_header() << '\n';
    for (const Row& row : rows) {
      const std::string& line = lines[row.point];
      out << (line.empty() ? csv_line(row) : line) << '\n';
    }
  };
  if (flags.out.empty())
    write_to_stdout(csv);
  else
    write_atomically(flags.out, csv);
}

}  // namespace

CLI::App* add_spectrum_command(CLI::App& app, SpectrumFlags& flags) {
  CLI::App* command =
      app.add_subcommand("spectrum", "Solve every case of a case-set file; one CSV row per case, in point order");
  command->add_option("CASESET", flags.case_set, "Case-set file (TOML, see cases/README.md)")->required();
  add_solver_flags(*command, flags.solver_flags);
  command->add_option("--out", flags.out, "Write the CSV to this file (default: stdout)");
  command->add_option("--threads", flags.threads, "Worker threads (default: all cores)");
  add_repetitions_flag(*command, flags.repetitions);
  return command;
}

int spectrum_command(const CLI::App& command, const SpectrumFlags& flags, const Processes& processes) {
  // Everything is checked before the first file is created.
  CaseSet set;
  std::vector<SweepRun> runs(1);
  std::vector<Row> earlier;
  const std::string partial = partial_file_name(flags.out, "spectrum");
  OutputLock lock;  // held until the output is written and the partial file removed
  processes.agree([&] {
    set = load_case_set(flags.case_set);
    validate_case_set(set, flags.case_set);
    runs[0] = {&checked_solver(flags.solver_flags, command), flags.solver_flags.settings, flags.repetitions};
    if (command.count("--threads") && flags.threads == 0) throw BadInput("--threads: must be >= 1");
    if (!processes.leader()) return;
    std::vector<NamedFile> inputs = record_files(set.cases);
    inputs.push_back({"CASESET", flags.case_set});
    check_outputs_apart({{"--out", flags.out}}, inputs, partial, lock_file_name(flags.out, "spectrum"));
    if (!flags.out.empty()) check_sweep_output(flags.out, "--out");
    lock = take_output_lock(flags.out, "spectrum", partial);
    earlier = read_earlier_rows(partial, set.cases, runs);
  }, exit_code_of);

  std::vector<std::string> lines;
  const auto rows = run_resumable("spectrum", processes, set.cases, runs, partial, lock, std::move(earlier),
                                  flags.threads, &lines);
  if (!rows) return kInterrupted;
  if (!processes.leader()) return 0;
  write_outputs(partial, [&] { write_final(flags, *rows, lines); });
  report_written(rows->size(), flags.out);
  return 0;
}

}  // namespace pb::app
