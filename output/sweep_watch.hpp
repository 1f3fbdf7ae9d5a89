#pragma once
// Watches a running sweep from a thread of its own: shows its progress on stderr (when the
// sweep lasts more than a second) and turns SIGINT/SIGTERM into the sweep's cancel flag.
// Progress is a bar redrawn in place on a terminal, or a plain line (progress_line) every
// ten seconds where stderr is a file or a pipe (a batch job's log, an MPI job's rank 0,
// whose stderr mpirun forwards). Once its outputs are written, a sweep command says so in
// a last line per file (report_written).
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
//
// The watcher wakes every tick (100 ms) on a condition variable, and finish() wakes it at
// once: it used to wait in sigtimedwait for the tick's end, so that every sweep ended up to
// 100 ms after its last point. Signals are taken at each wake-up (sigtimedwait with no
// wait), so a Ctrl-C is acted on within one tick rather than at once; the bar never showed
// faster than that. `on_tick`, when given, runs on the watcher's thread at every wake-up
// but the last (a resumed sweep flushes its partial file there: output/resumable_sweep.cpp).

#include <signal.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>

namespace pb::app {

enum class Progress { none, bar, lines };

// A bar on a terminal, plain lines elsewhere; none on the processes of a job but its leader.
Progress progress_on_stderr(bool leader);

// A duration as people say it: "12 s", "3 min", "1.5 h".
inline std::string rough_duration(double seconds) {
  char text[32];
  if (seconds < 90)
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  else if (seconds < 5400)
    std::snprintf(text, sizeof text, "%.0f min", seconds / 60);
  else
    std::snprintf(text, sizeof text, "%.1f h", seconds / 3600);
  return text;
}

// The plain progress line, without its "poundbench: " and line end:
// "spectrum: 1234/23820 points, 12 s, about 3 min left". The time left is `left` when given
// (output/cost_left.hpp: from the cost of what is left), else extrapolated from the rate of this
// run (the `resumed` tasks an earlier run did are not in it), and missing until a task is
// done. Inline: the tests, which do not link the command line, check it.
inline std::string progress_line(std::string_view command, std::string_view unit, std::size_t done,
                                 std::size_t total, std::size_t resumed, double elapsed, bool stopping,
                                 std::optional<double> left = std::nullopt) {
  std::string line = std::string(command) + ": " + std::to_string(done) + "/" + std::to_string(total) + " " +
                     std::string(unit) + ", " + rough_duration(elapsed);
  if (stopping) return line + ", stopping (a second Ctrl-C abandons the running ones)";
  if (done > resumed && done < total)
    line += ", about " +
            rough_duration(left ? *left
                                : static_cast<double>(total - done) * elapsed / static_cast<double>(done - resumed)) +
            " left";
  return line;
}

// The last line of a sweep command, on stderr, once per output file it wrote:
// "poundbench: wrote N rows to FILE in T s" ("" is stdout), T from the start of the process,
// then "; NOTE" when a note is given (what failed: failed_note).
void report_written(std::size_t rows, const std::string& file, std::string_view note = {});

// "40 runs did not finish ok (status not ok; --check makes that exit 1)": the note of a
// closing line whose rows hold failures, so that a sweep whose every point failed does not
// read as a success. `checked`: --check was given (it will say more).
std::string failed_note(std::size_t failed, std::string_view unit, bool checked);

class SweepWatch {
 public:
  // command, unit: for progress_line ("spectrum", "points"). resumed: of the total, the
  // tasks an earlier run finished (not counted in the rate).
  // left: seconds left after so many elapsed (output/cost_left.hpp), for the progress; none, or
  // nullopt from it: from the count.
  using Left = std::function<std::optional<double>(double elapsed)>;
  SweepWatch(std::string command, std::string unit, std::size_t total, std::size_t resumed, Progress progress,
             std::function<void()> abandon, std::function<void()> on_tick = {}, Left left = {});
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

  std::string command_;
  std::string unit_;
  std::size_t total_;
  std::size_t resumed_;
  Progress progress_;
  std::function<void()> abandon_;
  std::function<void()> on_tick_;
  Left left_;
  sigset_t signals_;  // the ones the watcher takes
  struct sigaction previous_[2] = {};  // SIGINT's and SIGTERM's actions before the watcher
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::atomic<std::size_t> done_;
  std::atomic<bool> cancel_{false};
  std::atomic<bool> finished_{false};
  std::mutex wake_mutex_;  // with wake_: finish() ends the watcher's wait at once
  std::condition_variable wake_;
  bool drawn_ = false;  // a bar is on the screen
  std::chrono::steady_clock::time_point last_line_ = start_;
  std::thread thread_;
};

}  // namespace pb::app
