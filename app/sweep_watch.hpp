#pragma once
// Watches a running sweep from a thread of its own: shows its progress on stderr (when the
// sweep lasts more than a second) and turns SIGINT/SIGTERM into the sweep's cancel flag.
// Progress is a bar redrawn in place on a terminal, or a plain line every ten seconds
// where stderr is a pipe that a person may still watch (an MPI job's rank 0, whose stderr
// mpirun forwards, or a batch job's log).
//
// Signals are blocked in the constructing thread, so every thread started after it (the
// sweep's workers) inherits the block and only the watcher, waiting in sigtimedwait,
// receives them. A signal the process was started with ignored stays ignored. This avoids
// doing anything in a signal handler, but for threads started before main (a library's
// workers, such as OpenBLAS's), which may not block them: a signal delivered to one of those
// is recorded by a handler, installed while the watcher runs, and taken by the watcher at its
// next tick. A first signal cancels (no new points start; running ones finish); a second one
// calls `abandon`, which must not return (it ends the process without waiting for the
// running points).

#include <signal.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <thread>

namespace pb::app {

enum class Progress { none, bar, lines };

class SweepWatch {
 public:
  // resumed: of the total, the points an earlier run finished (not counted in the rate).
  SweepWatch(std::size_t total, std::size_t resumed, Progress progress, std::function<void()> abandon);
  ~SweepWatch();
  SweepWatch(const SweepWatch&) = delete;
  SweepWatch& operator=(const SweepWatch&) = delete;

  const std::atomic<bool>& cancel() const { return cancel_; }
  void set_done(std::size_t done) { done_ = done; }
  // Stops the watcher and erases the progress bar. Signals stay blocked afterwards.
  void finish();
  bool interrupted() const { return cancel_; }

 private:
  void watch();
  void draw(bool stopping);

  std::size_t total_;
  std::size_t resumed_;
  Progress progress_;
  std::function<void()> abandon_;
  sigset_t signals_;  // the ones the watcher takes
  struct sigaction previous_[2] = {};  // SIGINT's and SIGTERM's actions before the watcher
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::atomic<std::size_t> done_;
  std::atomic<bool> cancel_{false};
  std::atomic<bool> finished_{false};
  bool drawn_ = false;  // a bar is on the screen
  std::chrono::steady_clock::time_point last_line_ = start_;
  std::thread thread_;
};

}  // namespace pb::app
