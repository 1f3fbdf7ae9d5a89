#include "app/resumable_sweep.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <stdexcept>

#include "app/errors.hpp"
#include "app/output_files.hpp"
#include "app/sweep_watch.hpp"
#include "solvers/external/process.hpp"
#include "sweep/partial_rows.hpp"

namespace pb::app {

std::string partial_file_name(const std::string& out, std::string_view command) {
  return out.empty() ? "poundbench-" + std::string(command) + ".partial.csv" : out + ".partial";
}

OutputLock take_output_lock(const std::string& out, std::string_view command, const std::string& partial) {
  check_output_target(partial, "partial file");  // before the lock names the same directory
  const std::string lock_file = lock_file_name(out, command);
  check_output_target(lock_file, "lock file");
  return OutputLock(lock_file, out.empty() ? "partial file: " + partial : "--out: " + out);
}

std::vector<Row> read_earlier_rows(const std::string& partial, std::span<const Case> cases,
                                   std::span<const SweepRun> runs) {
  check_output_target(partial, "partial file");
  std::error_code ec;
  if (!std::filesystem::exists(partial, ec)) return {};
  std::ifstream in(partial);
  if (!in) throw BadInput("partial file: " + partial + ": cannot be read");
  try {
    return read_partial_rows(in, partial, cases, runs);
  } catch (const PartialRowsError& e) {
    throw BadInput(e.what());
  }
}

std::optional<std::vector<Row>> run_resumable(std::string_view command, const Processes& processes,
                                              std::span<const Case> cases, std::span<const SweepRun> runs,
                                              const std::string& partial, OutputLock& lock, std::vector<Row> earlier,
                                              unsigned threads) {
  const std::size_t total = cases.size() * runs.size();
  const bool with_run = runs.size() > 1;
  std::vector<std::size_t> todo;
  std::optional<FlushedFile> file;
  if (processes.leader()) {
    todo = missing_tasks(earlier, cases.size(), runs.size());
    write_atomically(partial, [&](std::ostream& out) {
      out << partial_header(with_run) << '\n';
      for (const Row& row : earlier) out << partial_line(row, with_run) << '\n';
    });
    file.emplace(partial, FlushedFile::Mode::append);
  }

  std::mutex file_mutex;  // held while a row is written, so an abandon never cuts a line
  const Progress progress = progress_on_stderr(processes.leader());
  const char* unit = runs.size() == 1 ? "points" : "runs";
  const auto abandon = [&] {
    file_mutex.lock();
    // Erases the bar; on a file or a pipe the escape sequence would be garbage in the log.
    const char* erase = progress == Progress::bar ? "\r\033[K" : "";
    if (processes.leader())
      std::fprintf(stderr, "%spoundbench: interrupted; the finished rows are in %s\n", erase, partial.c_str());
    std::fflush(stderr);
    lock.release();  // _Exit runs no destructor
    external::end_running_programs();  // the external solver's, in process groups of their own
    std::_Exit(kInterrupted);
  };
  SweepWatch watch(std::string(command), unit, total, earlier.size(), progress, abandon);

  SweepOptions options;
  options.threads = threads ? threads : processes.default_threads();
  options.cancel = &watch.cancel();
  if (file) {
    options.on_row = [&](const Row& row) {
      const std::lock_guard hold(file_mutex);
      file->write_line(partial_line(row, with_run));
    };
    options.on_progress = [&](std::size_t done, std::size_t) { watch.set_done(earlier.size() + done); };
  }

  std::vector<Row> rows;
  try {
    rows = processes.sweep(cases, runs, todo, options);
  } catch (const std::exception& e) {
    watch.finish();
    if (!file) throw;
    throw std::runtime_error(std::string(e.what()) + " (finished rows are in " + partial + ")");
  }
  watch.finish();
  if (!file) return std::vector<Row>{};
  file->close();

  rows.insert(rows.end(), std::make_move_iterator(earlier.begin()), std::make_move_iterator(earlier.end()));
  std::sort(rows.begin(), rows.end(), task_order);
  if (rows.size() < total) {
    std::fprintf(stderr, "poundbench: interrupted after %zu of %zu %s; the finished rows are in %s\n", rows.size(),
                 total, unit, partial.c_str());
    return std::nullopt;
  }
  return rows;
}

void write_outputs(const std::string& partial, const std::function<void()>& write) {
  try {
    write();
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string(e.what()) + "; every finished row is kept in " + partial +
                             ": rerun the same command to write the output from it");
  }
  std::error_code ec;
  std::filesystem::remove(partial, ec);
}

}  // namespace pb::app
