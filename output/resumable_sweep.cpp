#include "output/resumable_sweep.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "output/cost_left.hpp"
#include "output/output_files.hpp"
#include "output/partial_writer.hpp"
#include "output/sweep_watch.hpp"
#include "cases/input_file.hpp"
#include "frontend/errors.hpp"
#include "programs/process.hpp"
#include "output/partial_rows.hpp"

namespace pb::app {

std::string partial_file_name(const std::string& out, std::string_view command) {
  return out.empty() ? "poundbench-" + std::string(command) + ".partial.csv" : out + ".partial";
}

OutputLock take_output_lock(const std::string& out, std::string_view command, const std::string& partial) {
  // A partial file is read back: a FIFO or a device there is refused as an input is.
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(partial, ec);
  if (!ec && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st)) {
    std::string text;
    throw BadInput("partial file: " + cannot_read(partial, read_regular_file(partial, text).value_or("not a regular file")));
  }
  check_output_target(partial, "partial file");  // before the lock names the same directory
  const std::string lock_file = lock_file_name(out, command);
  check_output_target(lock_file, "lock file");
  return OutputLock(lock_file, out.empty() ? "partial file: " + partial : "--out: " + out);
}

namespace {

// The rows of the partial file, checked (output/partial_rows.hpp), to `each` in the file's
// order, read as a stream; BadInput when it cannot be read or is another sweep's. Nothing
// when it does not exist.
void each_partial_row(const std::string& partial, const CaseList& cases, std::span<const SweepRun> runs,
                      const std::function<void(Row&&)>& each, PartialFileShape* shape = nullptr) {
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(partial, ec))) return;
  if (const std::optional<std::string> why = regular_file_problem(partial))
    throw BadInput("partial file: " + cannot_read(partial, *why));
  std::ifstream in(partial, std::ios::binary);
  if (!in) throw BadInput("partial file: " + cannot_read(partial, std::strerror(errno)));
  try {
    for_each_partial_row(in, partial, cases, runs, each, shape);
  } catch (const PartialRowsError& e) {
    throw BadInput(e.what());
  }
  if (in.bad()) throw BadInput("partial file: " + cannot_read(partial, "read error"));
}

}  // namespace

EarlierRows read_earlier_rows(const std::string& partial, const CaseList& cases, std::span<const SweepRun> runs,
                              bool keep) {
  check_output_target(partial, "partial file");
  EarlierRows earlier;
  earlier.done.assign(cases.size() * runs.size(), false);
  each_partial_row(partial, cases, runs, [&](Row&& row) {
    earlier.done[row.run * cases.size() + row.point] = true;
    ++earlier.count;
    if (keep) earlier.rows.push_back(std::move(row));
  }, &earlier.file);
  std::sort(earlier.rows.begin(), earlier.rows.end(), task_order);
  return earlier;
}

namespace {

// The tasks `earlier` lacks, in the order they are handed out; earlier.done is released.
std::vector<std::size_t> tasks_left(std::size_t points, std::size_t runs, EarlierRows& earlier) {
  const std::size_t total = points * runs;
  std::vector<std::size_t> todo;
  for (std::size_t t = 0; t < total; ++t)
    if (earlier.done.empty() || !earlier.done[t]) todo.push_back(t);
  std::vector<bool>().swap(earlier.done);
  // Several runs: handed out a point at a time, each point through every run in turn, not a
  // run at a time. Run after run, the threads took the same solver together, and Bullet's
  // Dantzig solves are taken one at a time (solvers/bullet/engine.cpp): the main job's
  // work-precision study would take 152 s on 2 threads by its rows' CPU times, against 145 s
  // a point at a time and 141 s at best. The rows are the same; only their order differs.
  if (runs > 1)
    std::stable_sort(todo.begin(), todo.end(),
                     [points](std::size_t a, std::size_t b) { return a % points < b % points; });
  return todo;
}

// The partial file made ready to append to: the rows read, a torn last line dropped:
// rewritten from the ones kept; else, when the file holds each as it would be written, cut
// after its last whole record; else rewritten from the file's own rows, streamed in its order
// (the output is copied in point order from the file either way).
void restore_partial_file(const std::string& partial, const CaseList& cases, std::span<const SweepRun> runs,
                          const EarlierRows& earlier) {
  const bool with_run = runs.size() > 1;
  if (earlier.rows.size() != earlier.count && earlier.file.as_printed) {
    std::filesystem::resize_file(partial, earlier.file.whole_bytes);
    return;
  }
  write_atomically(partial, [&](std::ostream& out) {
    out << partial_header(with_run) << '\n';
    if (earlier.rows.size() == earlier.count)
      for (const Row& row : earlier.rows) out << partial_line(row, with_run) << '\n';
    else
      each_partial_row(partial, cases, runs, [&](Row&& row) { out << partial_line(row, with_run) << '\n'; });
  });
}

// The sweep's rows; where it fails, the rows finished before are written first and the
// error says where they are.
std::vector<Row> sweep_keeping_finished(const Processes& processes, const CaseList& cases,
                                        std::span<const SweepRun> runs, const std::vector<std::size_t>& todo,
                                        const SweepOptions& options, SweepWatch& watch,
                                        std::optional<PartialWriter>& file, const std::string& partial) {
  try {
    return processes.sweep(cases, runs, todo, options);
  } catch (const std::exception& e) {
    watch.finish();
    if (!file) throw;
    try {
      file->write_all();  // the rows finished before the failure
    } catch (const std::exception&) {
      // The failure may be the file's own: the sweep's error says what happened.
    }
    throw std::runtime_error(std::string(e.what()) + " (finished rows are in " + partial + ")");
  }
}

}  // namespace

std::optional<std::vector<Row>> run_resumable(std::string_view command, const Processes& processes,
                                              const CaseList& cases, std::span<const SweepRun> runs,
                                              const std::string& partial, OutputLock& lock, EarlierRows earlier,
                                              unsigned threads, std::vector<std::string>* lines, bool keep_rows) {
  const std::size_t total = cases.size() * runs.size();
  const bool with_run = runs.size() > 1;
  const std::size_t resumed = earlier.count;
  std::vector<std::size_t> todo;
  std::optional<PartialWriter> file;
  if (processes.leader()) {
    todo = tasks_left(cases.size(), runs.size(), earlier);
    restore_partial_file(partial, cases, runs, earlier);
    if (!keep_rows) std::vector<Row>().swap(earlier.rows);  // in the file now, which is where the output comes from
    if (lines) lines->assign(total, std::string());
    file.emplace(partial, with_run, cases.size(), lines, todo.size());
  }

  const Progress progress = progress_on_stderr(processes.leader());
  const char* unit = runs.size() == 1 ? "points" : "runs";
  const auto abandon = [&] {
    if (file) {
      try {
        file->write_all();  // the finished rows queued for the next batch
      } catch (const std::exception&) {
        // Ending anyway: the rows already in the file are kept.
      }
    }
    // Erases the bar; on a file or a pipe the escape sequence would be garbage in the log.
    const char* erase = progress == Progress::bar ? "\r\033[K" : "";
    if (processes.leader())
      std::fprintf(stderr, "%spoundbench: interrupted; the finished rows are in %s\n", erase, partial.c_str());
    std::fflush(stderr);
    lock.release();  // _Exit runs no destructor
    programs::end_running_programs();  // the external solver's, in process groups of their own
    std::_Exit(kInterrupted);
  };
  const auto write_due = [&] {
    if (file) file->write_due();
  };
  CostLeft cost_left(runs, cases.size(), todo);
  SweepWatch::Left left;
  if (runs.size() > 1) left = [&](double elapsed) { return cost_left.seconds_left(elapsed); };
  SweepWatch watch(std::string(command), unit, total, resumed, progress, abandon, write_due, left);

  SweepOptions options;
  options.threads = threads ? threads : processes.default_threads();
  options.cancel = &watch.cancel();
  options.keep_rows = keep_rows;
  std::size_t finished = resumed;
  if (file) {
    options.on_finished = [&](const Row& row) { file->queue(row); };
    options.on_row = [&](const Row& row) { cost_left.add(row); };
    options.on_progress = [&](std::size_t done, std::size_t) { watch.set_done(finished = resumed + done); };
  }

  std::vector<Row> rows = sweep_keeping_finished(processes, cases, runs, todo, options, watch, file, partial);
  watch.finish();
  if (!file) return std::vector<Row>{};
  file->write_all();
  file->close();

  rows.insert(rows.end(), std::make_move_iterator(earlier.rows.begin()), std::make_move_iterator(earlier.rows.end()));
  std::sort(rows.begin(), rows.end(), task_order);
  if (finished < total) {
    std::fprintf(stderr, "poundbench: interrupted after %zu of %zu %s; the finished rows are in %s\n", finished,
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
