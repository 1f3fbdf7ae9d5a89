#pragma once
// The partial file's writer (output/resumable_sweep.hpp): the finished rows a sweep queues, written
// in batches.
//
// Each row used to be formatted and written, flushed, by the worker that finished it, under
// the sweep's lock (sweep/sweep.hpp: the callbacks are serialised): on the paper set, 23 820
// writes and 6 426 contended locks. Now the worker that finished a row formats its line
// outside that lock (SweepOptions::on_finished), side by side with the other workers, and
// queues the line; the watcher's thread writes the queued lines in one batch (BatchedFile)
// once the oldest has waited kPartialDelay or kBatchRows are queued, and the caller writes
// what is left when the sweep has ended. (The queue held copies of the rows, formatted in
// batches: a row's copy, some 1.5 KB and its strings, was 5 % of the paper set's sweep
// through the reference, the rows' copies and their page faults, perf's cpu-clock.)
//
// The queue is bounded: a worker whose row would make it hold more than kMaxQueued rows
// writes the queue itself before it goes on, and the sweep's other workers wait for it at
// their next row. Unbounded, a sweep whose points finish
// faster than the watcher's ticks write them (Moreau-Jean at 8 steps a period: 40 000 points
// a second on two threads) held rows at 1.5 KB each for as long as it outran the file (issue
// 36: memory flat in the points).
//
// Writes are serialised among the watcher, the workers and the caller. A failed write is
// kept and thrown to the next row's worker, which stops the sweep, and at write_all().

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>
#include <vector>

#include "output/output_files.hpp"
#include "rows/row.hpp"

namespace pb::app {

// How long a finished row may wait in memory before it is written to the partial file. A
// row reaches the file at most kPartialDelay plus one tick of the watcher (100 ms,
// output/sweep_watch.cpp) after it reached the leader; an interrupt by signal loses nothing
// finished (the rows queued are written as the sweep stops, and before the process ends on
// a second signal), and a kill or a crash the rows of the last 0.6 s at most.
inline constexpr auto kPartialDelay = std::chrono::milliseconds(500);

class PartialWriter {
 public:
  // A batch is written at the watcher's next tick once it holds kBatchRows rows, whatever
  // their age; a worker writes it at once at kMaxQueued (about 4 MB of lines).
  static constexpr std::size_t kBatchRows = 4096;
  static constexpr std::size_t kMaxQueued = 2 * kBatchRows;

  // with_run: the partial file's run column (output/partial_rows.hpp). lines, when given,
  // receives each row's line by task (run * cases + point). expected: the rows the sweep will
  // queue, so that the queue takes room for no more than those still to come.
  PartialWriter(const std::string& partial, bool with_run, std::size_t cases, std::vector<std::string>* lines,
                std::size_t expected);

  // A finished row, from the sweep's worker (several threads at once): its line is made on
  // the calling thread and queued.
  void queue(const Row& row);
  // The watcher's tick: writes the queued rows once the oldest has waited long enough.
  void write_due();
  // Every queued row, now; throws a failed write's error.
  void write_all() { write(true); }
  void close();

  // The most rows the queue held at once.
  std::size_t peak_queued() const;

 private:
  using Clock = std::chrono::steady_clock;
  void write(bool all);
  std::size_t room() const { return std::min(to_come_, kMaxQueued); }

  struct Line {
    std::string text;
    std::size_t task;  // run * cases + point
  };

  std::mutex writing_;  // held by the one thread that writes; taken before mutex_
  BatchedFile file_;    // written in batches: its own size limit only (1 MiB), never its delay
  bool with_run_;
  std::size_t cases_;
  std::vector<std::string>* lines_;
  mutable std::mutex mutex_;  // guards what follows
  std::vector<Line> queued_;
  std::size_t to_come_;  // rows not queued yet
  std::size_t peak_ = 0;
  Clock::time_point oldest_{};
  std::string error_;  // a failed write's
};

}  // namespace pb::app
