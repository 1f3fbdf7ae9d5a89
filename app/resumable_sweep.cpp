#include "app/resumable_sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/cost_left.hpp"
#include "app/output_files.hpp"
#include "app/sweep_watch.hpp"
#include "cases/input_file.hpp"
#include "frontend/errors.hpp"
#include "solvers/external/process.hpp"
#include "sweep/partial_rows.hpp"

namespace pb::app {

namespace {

using Clock = std::chrono::steady_clock;

// How long a finished row may wait in memory before it is written to the partial file. A
// row reaches the file at most kPartialDelay plus one tick of the watcher (100 ms,
// app/sweep_watch.cpp) after it reached the leader; an interrupt by signal loses nothing
// finished (the rows queued are written as the sweep stops, and before the process ends on
// a second signal), and a kill or a crash the rows of the last 0.6 s at most.
constexpr auto kPartialDelay = std::chrono::milliseconds(500);

// The partial file's writer. Each row used to be formatted and written, flushed, by the
// worker that finished it, under the sweep's lock (sweep/sweep.hpp: the callbacks are
// serialised): on the paper set, 23 820 writes and 6 426 contended locks. Now a worker only
// queues a copy of its row; the watcher's thread formats the queued rows and writes them in
// one batch (BatchedFile) once the oldest has waited kPartialDelay, and the caller writes
// what is left when the sweep has ended. One thread writes at a time: the watcher while the
// sweep runs (its ticks and its abandon are one thread), the caller after watch.finish().
// A failed write is kept and thrown to the next row's worker, which stops the sweep, and at
// write_all().
class PartialWriter {
 public:
  // `expected`: the rows the sweep will queue; the queue takes room for those still to come
  // at each batch. Grown row by row, it was copied as it doubled, under the sweep's lock.
  PartialWriter(const std::string& partial, bool with_run, std::size_t cases, std::vector<std::string>* lines,
                unsigned threads, std::size_t expected)
      : file_(partial, BatchedFile::Mode::append, Clock::duration::max()),
        with_run_(with_run),
        cases_(cases),
        lines_(lines),
        threads_(std::max(threads, 1u)),
        to_come_(expected) {
    queued_.reserve(room());
  }

  // A finished row, from the sweep's callback (any thread, serialised).
  void queue(const Row& row) {
    const std::lock_guard hold(mutex_);
    if (!error_.empty()) throw std::runtime_error(error_);
    if (queued_.empty()) oldest_ = Clock::now();
    queued_.push_back(row);
  }
  // The watcher's tick: writes the queued rows once the oldest has waited long enough.
  void write_due() {
    try {
      write(false);
    } catch (const std::exception&) {
      // Kept in error_ for the next row's worker.
    }
  }
  // Every queued row, now; throws a failed write's error.
  void write_all() { write(true); }
  void close() { file_.close(); }

 private:
  void write(bool all) {
    std::vector<Row> rows;
    {
      const std::lock_guard hold(mutex_);
      if (!error_.empty()) throw std::runtime_error(error_);
      if (queued_.empty() || (!all && Clock::now() - oldest_ < kPartialDelay && queued_.size() < kBatchRows)) return;
      rows.swap(queued_);
      to_come_ -= std::min(to_come_, rows.size());
      queued_.reserve(room());
    }
    try {
      std::vector<std::string> text = format(rows);
      for (std::size_t i = 0; i < rows.size(); ++i) {
        file_.add_line(text[i]);
        if (lines_) (*lines_)[rows[i].run * cases_ + rows[i].point] = std::move(text[i]);
      }
      file_.flush();
    } catch (const std::exception& e) {
      const std::lock_guard hold(mutex_);
      error_ = e.what();
      throw;
    }
  }

  // The rows' lines, on the sweep's threads when there are many: a sweep shorter than
  // kPartialDelay (the paper set through the reference, 0.3 s) leaves every row to the last
  // batch, written after the workers have stopped, and its 23 820 lines took 0.1 s on one.
  std::vector<std::string> format(const std::vector<Row>& rows) const {
    std::vector<std::string> text(rows.size());
    const std::size_t n = rows.size(), ways = n < 1024 ? 1 : threads_;
    const auto part = [&](std::size_t first) {
      for (std::size_t i = first; i < n; i += ways) text[i] = partial_line(rows[i], with_run_);
    };
    {
      std::vector<std::jthread> pool;
      for (std::size_t w = 1; w < ways; ++w) pool.emplace_back(part, w);
      part(0);
    }  // the jthreads join here, before text is returned
    return text;
  }

  // A batch is written at the watcher's next tick once it holds kBatchRows rows, whatever their
  // age, and the queue takes room for no more than that at a time: with room for every row to
  // come, a million-point sweep reserved 1.5 GB up front.
  static constexpr std::size_t kBatchRows = 4096;
  std::size_t room() const { return std::min(to_come_, 2 * kBatchRows); }

  BatchedFile file_;  // written in batches: its own size limit only (1 MiB), never its delay
  bool with_run_;
  std::size_t cases_;
  std::vector<std::string>* lines_;
  unsigned threads_;
  std::mutex mutex_;  // guards what follows
  std::vector<Row> queued_;
  std::size_t to_come_;  // rows not queued yet
  Clock::time_point oldest_{};
  std::string error_;  // a failed write's
};

}  // namespace

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

std::vector<Row> read_earlier_rows(const std::string& partial, std::span<const Case> cases,
                                   std::span<const SweepRun> runs) {
  check_output_target(partial, "partial file");
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(partial, ec))) return {};
  std::string text;
  if (const std::optional<std::string> why = read_regular_file(partial, text))
    throw BadInput("partial file: " + cannot_read(partial, *why));
  std::istringstream in(std::move(text));
  try {
    return read_partial_rows(in, partial, cases, runs);
  } catch (const PartialRowsError& e) {
    throw BadInput(e.what());
  }
}

std::optional<std::vector<Row>> run_resumable(std::string_view command, const Processes& processes,
                                              std::span<const Case> cases, std::span<const SweepRun> runs,
                                              const std::string& partial, OutputLock& lock, std::vector<Row> earlier,
                                              unsigned threads, std::vector<std::string>* lines, bool keep_rows) {
  const std::size_t total = cases.size() * runs.size();
  const bool with_run = runs.size() > 1;
  const std::size_t resumed = earlier.size();
  std::vector<std::size_t> todo;
  std::optional<PartialWriter> file;
  if (processes.leader()) {
    todo = missing_tasks(earlier, cases.size(), runs.size());
    write_atomically(partial, [&](std::ostream& out) {
      out << partial_header(with_run) << '\n';
      for (const Row& row : earlier) out << partial_line(row, with_run) << '\n';
    });
    if (!keep_rows) std::vector<Row>().swap(earlier);  // in the file now, which is where the output comes from
    if (lines) lines->assign(total, std::string());
    file.emplace(partial, with_run, cases.size(), lines, threads ? threads : processes.default_threads(),
                 todo.size());
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
    external::end_running_programs();  // the external solver's, in process groups of their own
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
    options.on_row = [&](const Row& row) {
      file->queue(row);
      cost_left.add(row);
    };
    options.on_progress = [&](std::size_t done, std::size_t) { watch.set_done(finished = resumed + done); };
  }

  std::vector<Row> rows;
  try {
    rows = processes.sweep(cases, runs, todo, options);
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
  watch.finish();
  if (!file) return std::vector<Row>{};
  file->write_all();
  file->close();

  rows.insert(rows.end(), std::make_move_iterator(earlier.begin()), std::make_move_iterator(earlier.end()));
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
