#include "app/spectrum_command.hpp"

#include <algorithm>
#include <iostream>
#include <stdexcept>

#include "app/check_report.hpp"
#include "app/output_files.hpp"
#include "app/resumable_sweep.hpp"
#include "app/study_run.hpp"
#include "app/sweep_watch.hpp"
#include "cases/case_set.hpp"
#include "frontend/case_flags.hpp"
#include "frontend/errors.hpp"
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

// --check: a verdict per family, failing when a point of it did not finish ok; the line
// names the first few such points, their status and the first one's message.
std::vector<Verdict> verdicts(const std::vector<Row>& rows) {
  constexpr std::size_t kListedPoints = 5;
  std::vector<std::string> families;
  std::vector<std::vector<const Row*>> failed;
  std::vector<std::size_t> points;
  for (const Row& r : rows) {
    auto at = std::find(families.begin(), families.end(), r.input.family);
    if (at == families.end()) {
      families.push_back(r.input.family);
      failed.emplace_back();
      points.push_back(0);
      at = families.end() - 1;
    }
    const std::size_t f = static_cast<std::size_t>(at - families.begin());
    ++points[f];
    if (r.result.status != Status::ok) failed[f].push_back(&r);
  }
  std::vector<Verdict> out;
  for (std::size_t f = 0; f < families.size(); ++f) {
    std::string failure;
    if (!failed[f].empty()) {
      failure = std::to_string(failed[f].size()) + " of " + std::to_string(points[f]) + " points did not finish ok (";
      for (std::size_t i = 0; i < failed[f].size() && i < kListedPoints; ++i)
        failure += (i ? ", " : "") + std::string("point ") + std::to_string(failed[f][i]->point) + " " +
                   std::string(name(failed[f][i]->result.status));
      if (failed[f].size() > kListedPoints)
        failure += " and " + std::to_string(failed[f].size() - kListedPoints) + " more";
      failure += ")";
      if (!failed[f][0]->result.message.empty()) failure += "; the first: " + failed[f][0]->result.message;
    }
    out.push_back({"spectrum", "family " + families[f], failure});
  }
  return out;
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
  command->add_flag(
      "--check", flags.check,
      "Exit 1 when a point did not finish ok (after writing the output), naming them on stderr per family");
  add_junit_flag(*command, flags.junit, "family");
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
    check_junit_target(flags.junit, flags.check);
    lock = take_output_lock(flags.out, "spectrum", partial);
    earlier = read_earlier_rows(partial, set.cases, runs);
  }, exit_code_of);

  std::vector<std::string> lines;
  const auto rows = run_resumable("spectrum", processes, set.cases, runs, partial, lock, std::move(earlier),
                                  flags.threads, &lines);
  if (!rows) return kInterrupted;
  if (!processes.leader()) return 0;
  write_outputs(partial, [&] { write_final(flags, *rows, lines); });
  const std::size_t failed = static_cast<std::size_t>(
      std::count_if(rows->begin(), rows->end(), [](const Row& r) { return r.result.status != Status::ok; }));
  report_written(rows->size(), flags.out, failed ? failed_note(failed, "points", flags.check) : "");
  return flags.check ? report_check("spectrum", verdicts(*rows), "families", flags.junit) : 0;
}

}  // namespace pb::app
