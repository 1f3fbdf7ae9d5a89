#include "app/spectrum_command.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <stdexcept>

#include "app/errors.hpp"
#include "app/output_files.hpp"
#include "app/sweep_watch.hpp"
#include "cases/case_set.hpp"
#include "sweep/sweep.hpp"

namespace pb::app {

namespace {

constexpr int kInterrupted = 130;

void validate_cases(const CaseSet& set, const std::string& file) {
  if (set.cases.empty()) throw BadInput(file + ": no cases");
  for (std::size_t i = 0; i < set.cases.size(); ++i)
    if (auto bad = validate(set.cases[i])) throw BadInput(file + ": point " + std::to_string(i) + ": " + *bad);
}

void write_final(const SpectrumFlags& flags, const std::vector<Row>& rows) {
  if (!flags.out.empty()) {
    write_atomically(flags.out, [&](std::ostream& out) { write_csv(out, rows); });
    return;
  }
  write_csv(std::cout, rows);
  std::cout.flush();
  if (!std::cout) throw std::runtime_error("stdout: write failed");
}

}  // namespace

std::string partial_file_name(const std::string& out) {
  return out.empty() ? "poundbench-spectrum.partial.csv" : out + ".partial";
}

CLI::App* add_spectrum_command(CLI::App& app, SpectrumFlags& flags) {
  CLI::App* command =
      app.add_subcommand("spectrum", "Solve every case of a case-set file; one CSV row per case, in point order");
  command->add_option("CASESET", flags.case_set, "Case-set file (TOML, see cases/README.md)")->required();
  add_solver_flags(*command, flags.solver_flags);
  command->add_option("--out", flags.out, "Write the CSV to this file (default: stdout)");
  command->add_option("--threads", flags.threads, "Worker threads (default: all cores)");
  return command;
}

int spectrum_command(const CLI::App& command, const SpectrumFlags& flags) {
  // Everything is checked before the first file is created.
  const CaseSet set = load_case_set(flags.case_set);
  validate_cases(set, flags.case_set);
  const SolverInfo& solver = checked_solver(flags.solver_flags);
  if (command.count("--threads") && flags.threads == 0) throw BadInput("--threads: must be >= 1");
  const std::string partial_name = partial_file_name(flags.out);
  if (!flags.out.empty())
    check_output_target(flags.out, "--out");
  else
    check_output_target(partial_name, "partial file (current directory)");

  const std::size_t total = set.cases.size();
  FlushedFile partial(partial_name);
  partial.write_line(csv_header());

  std::mutex partial_mutex;  // held while a row is written, so an abandon never cuts a line
  const auto abandon = [&] {
    partial_mutex.lock();
    std::fprintf(stderr, "\r\033[Kpoundbench: interrupted; the finished rows are in %s\n", partial_name.c_str());
    std::fflush(stderr);
    std::_Exit(kInterrupted);
  };
  SweepWatch watch(total, ::isatty(STDERR_FILENO) == 1, abandon);

  SweepOptions options;
  options.threads = flags.threads;
  options.cancel = &watch.cancel();
  options.on_row = [&](const Row& row) {
    const std::lock_guard lock(partial_mutex);
    partial.write_line(csv_line(row));
  };
  options.on_progress = [&](std::size_t done, std::size_t) { watch.set_done(done); };

  std::vector<Row> rows;
  try {
    rows = run_sweep(set.cases, solver, flags.solver_flags.settings, options);
  } catch (const std::exception& e) {
    watch.finish();
    throw std::runtime_error(std::string(e.what()) + " (finished rows are in " + partial_name + ")");
  }
  watch.finish();
  partial.close();

  if (rows.size() < total) {
    std::fprintf(stderr, "poundbench: interrupted after %zu of %zu points; the finished rows are in %s\n",
                 rows.size(), total, partial_name.c_str());
    return kInterrupted;
  }
  write_final(flags, rows);
  std::error_code ec;
  std::filesystem::remove(partial_name, ec);
  return 0;
}

}  // namespace pb::app
