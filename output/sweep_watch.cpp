#include "output/sweep_watch.hpp"

#include <signal.h>

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <string>

namespace pb::app {

namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kTick = std::chrono::milliseconds(100);  // at most ten redraws a second
constexpr auto kQuietStart = std::chrono::seconds(1);   // short sweeps show no bar
constexpr auto kLineEvery = std::chrono::seconds(10);  // Progress::lines
// Static initialisation, before main: what report_written counts from.
const Clock::time_point kProcessStart = Clock::now();

// SIGINT and SIGTERM, but not one that this process was started with ignored: a shell
// does that to a background job so that a Ctrl-C meant for the foreground leaves it alone.
sigset_t stop_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction action {};
    if (sigaction(sig, nullptr, &action) == 0 && action.sa_handler != SIG_IGN) sigaddset(&set, sig);
  }
  return set;
}

// A thread this process did not start may not block the stop signals: a library's worker
// made before main (OpenBLAS's, which Siconos' libraries load, starts one at load time). A
// signal delivered to it runs this handler, which only records it for the watcher.
volatile std::sig_atomic_t g_caught = 0;
extern "C" void record_signal(int sig) { g_caught = sig; }

std::string duration_text(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  char text[32];
  if (s >= 3600)
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
  return text;
}

}  // namespace

Progress progress_on_stderr(bool leader) {
  if (!leader) return Progress::none;
  return ::isatty(STDERR_FILENO) == 1 ? Progress::bar : Progress::lines;
}

void report_written(std::size_t rows, const std::string& file, std::string_view note) {
  const double seconds = std::chrono::duration<double>(Clock::now() - kProcessStart).count();
  std::fprintf(stderr, "poundbench: wrote %zu rows to %s in %.1f s%s%.*s\n", rows,
               file.empty() ? "stdout" : file.c_str(), seconds, note.empty() ? "" : "; ", static_cast<int>(note.size()),
               note.data());
  std::fflush(stderr);
}

std::string failed_note(std::size_t failed, std::string_view unit, bool checked) {
  return std::to_string(failed) + " " + std::string(unit) + " did not finish ok" +
         (checked ? "" : " (the status and message columns say why; --check makes this exit 1)");
}

SweepWatch::SweepWatch(std::string command, std::string unit, std::size_t total, std::size_t resumed,
                       Progress progress, std::function<void()> abandon, std::function<void()> on_tick, Left left)
    : command_(std::move(command)),
      unit_(std::move(unit)),
      total_(total),
      resumed_(resumed),
      progress_(progress),
      abandon_(std::move(abandon)),
      on_tick_(std::move(on_tick)),
      left_(std::move(left)),
      signals_(stop_signals()),
      done_(resumed) {
  pthread_sigmask(SIG_BLOCK, &signals_, nullptr);
  struct sigaction record {};
  record.sa_handler = record_signal;
  sigemptyset(&record.sa_mask);
  for (int sig : {SIGINT, SIGTERM})
    if (sigismember(&signals_, sig) == 1) sigaction(sig, &record, &previous_[sig == SIGINT ? 0 : 1]);
  thread_ = std::thread([this] { watch(); });
}

SweepWatch::~SweepWatch() { finish(); }

void SweepWatch::finish() {
  {
    // Under the mutex: the watcher tests finished_ and starts waiting with it held, so the
    // notification cannot fall between the two.
    const std::lock_guard lock(wake_mutex_);
    finished_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) {
    thread_.join();
    // A stopped sweep is on its way out (exit 130): its handler stays, so that a second
    // Ctrl-C arriving during the teardown is recorded, not taken by the default action
    // on whichever thread has the signal unblocked (the process would die by the signal).
    if (!cancel_)
      for (int sig : {SIGINT, SIGTERM})
        if (sigismember(&signals_, sig) == 1) sigaction(sig, &previous_[sig == SIGINT ? 0 : 1], nullptr);
  }
  if (drawn_) std::fputs("\r\033[K", stderr);
  drawn_ = false;
}

void SweepWatch::watch() {
  const timespec now{0, 0};  // sigtimedwait takes a pending signal without waiting
  while (true) {
    {
      std::unique_lock lock(wake_mutex_);
      if (wake_.wait_for(lock, kTick, [this] { return finished_.load(); })) return;
    }
    if (on_tick_) on_tick_();
    bool taken = false;
    while (sigtimedwait(&signals_, nullptr, &now) > 0) taken = true;  // signals do not queue: one or none
    if (taken || g_caught != 0) {
      g_caught = 0;
      if (cancel_) abandon_();
      cancel_ = true;
    }
    if (progress_ == Progress::none || finished_ || Clock::now() - start_ < kQuietStart) continue;
    if (progress_ == Progress::bar) {
      draw(cancel_);
    } else if (Clock::now() - last_line_ >= kLineEvery) {
      last_line_ = Clock::now();
      draw(cancel_);
    }
  }
}

void SweepWatch::draw(bool stopping) {
  const std::size_t done = done_;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  if (progress_ == Progress::lines) {
    const std::optional<double> left = left_ ? left_(elapsed) : std::nullopt;
    const std::string line = progress_line(command_, unit_, done, total_, resumed_, elapsed, stopping, left);
    std::fprintf(stderr, "poundbench: %s\n", line.c_str());
    std::fflush(stderr);
    return;
  }
  const double rate = static_cast<double>(done - resumed_) / elapsed;
  const double fraction = total_ ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
  constexpr int kWidth = 24;
  const int filled = static_cast<int>(fraction * kWidth);
  const std::string bar = std::string(static_cast<std::size_t>(filled), '#') +
                          std::string(static_cast<std::size_t>(kWidth - filled), '-');
  const std::optional<double> left = left_ && done > resumed_ ? left_(elapsed) : std::nullopt;
  const std::string eta =
      stopping           ? "stopping (Ctrl-C again to abandon running points)"
      : left             ? "ETA " + duration_text(*left)
      : done > resumed_  ? "ETA " + duration_text(static_cast<double>(total_ - done) / rate)
                         : "ETA --:--";
  std::fprintf(stderr, "\r\033[K[%s] %zu/%zu  %.*f %s/s  %s  elapsed %s", bar.c_str(), done, total_, rate < 10 ? 2 : 0,
               rate, unit_.c_str(), eta.c_str(), duration_text(elapsed).c_str());
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace pb::app
