#include "programs/process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/ioctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <system_error>
#include <utility>

#include "cases/text.hpp"
#include "programs/protocol.hpp"

extern char** environ;

namespace pb::programs {

namespace {

using Clock = std::chrono::steady_clock;

// How often the stop flag and the deadline are looked at while the program runs: a sweep
// stopped by Ctrl-C ends its programs within this. A wake-up costs a few microseconds.
constexpr double kPollSeconds = 0.01;
// Once the program has closed its stdout and stderr it is about to exit, and is waited for
// in naps from this, doubling up to kPollSeconds: a plain 10 ms nap there measured 10 ms of
// the 10.6 ms a point cost with a program that only answers.
constexpr double kFirstNap = 50e-6;
// How long a process the program left behind may hold its stdout or stderr open once the
// program itself has exited (a script's background child): then the group is ended.
constexpr double kDrainAfterExit = 0.2;
constexpr std::size_t kChunk = 1 << 16;

// The process groups of the programs running now (end_running_programs). A group leaves
// the set before its leader is reaped, under the lock, so that a pid the system has reused
// is never signalled.
std::mutex running_mutex;
std::set<pid_t> running;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

class Fd {
 public:
  Fd() = default;
  explicit Fd(int fd) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  Fd(Fd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  Fd& operator=(Fd&& other) noexcept {
    reset();
    fd_ = std::exchange(other.fd_, -1);
    return *this;
  }
  ~Fd() { reset(); }
  int get() const { return fd_; }
  bool open() const { return fd_ >= 0; }
  void reset() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_ = -1;
};

// A pipe whose ends are close-on-exec from the start and numbered above 2: with a standard
// stream of poundbench closed, pipe2 may return 0, 1 or 2, and a dup2 of a descriptor onto
// its own number would leave it close-on-exec, so that the program would start without it.
bool make_pipe(Fd& read_end, Fd& write_end) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) return false;
  for (int& fd : fds) {
    if (fd > 2) continue;
    const int moved = fcntl(fd, F_DUPFD_CLOEXEC, 3);
    ::close(fd);
    fd = moved;
  }
  read_end = Fd(fds[0]);
  write_end = Fd(fds[1]);
  return read_end.open() && write_end.open();
}

bool set_nonblocking(const Fd& fd) {
  const int flags = fcntl(fd.get(), F_GETFL);
  return flags >= 0 && fcntl(fd.get(), F_SETFL, flags | O_NONBLOCK) == 0;
}

// SIGPIPE blocked on a sweep's worker for as long as it works (ThreadSessionsEnd): its
// exchanges then need no mask of their own. Set and restored around each, with a look at what
// was pending, the mask was three system calls a point (issue 46). depth: the
// ThreadSessionsEnd scopes open on the thread; the mask is set at the first program run or
// exchange within one and restored as the last ends.
struct ThreadSigpipe {
  int depth = 0;
  bool blocked = false;
  bool was_pending = false;  // pending when it was blocked: not taken back
  sigset_t old{};
};
thread_local ThreadSigpipe thread_sigpipe;

sigset_t sigpipe_set() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGPIPE);
  return set;
}

bool sigpipe_pending() {
  sigset_t pending;
  sigemptyset(&pending);
  return sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE) == 1;
}

// Takes back a SIGPIPE this thread raised and blocked.
void take_back_sigpipe() {
  const sigset_t pipe = sigpipe_set();
  const timespec zero{};
  while (sigtimedwait(&pipe, nullptr, &zero) < 0 && errno == EINTR) {
  }
}

// SIGPIPE blocked in this thread while it lives (or, within a ThreadSessionsEnd scope, for as
// long as the scope: thread_sigpipe); a SIGPIPE that a write raised here is taken back before
// the old mask returns (one that was pending before is left alone).
class SigpipeBlock {
 public:
  SigpipeBlock() {
    const sigset_t pipe = sigpipe_set();
    if (thread_sigpipe.depth > 0) {
      shared_ = true;
      if (thread_sigpipe.blocked) return;
      thread_sigpipe.was_pending = sigpipe_pending();
      thread_sigpipe.blocked = pthread_sigmask(SIG_BLOCK, &pipe, &thread_sigpipe.old) == 0;
      return;
    }
    was_pending_ = sigpipe_pending();
    pthread_sigmask(SIG_BLOCK, &pipe, &old_);
  }
  SigpipeBlock(const SigpipeBlock&) = delete;
  SigpipeBlock& operator=(const SigpipeBlock&) = delete;
  ~SigpipeBlock() {
    if (raised_ && !(shared_ ? thread_sigpipe.was_pending : was_pending_)) take_back_sigpipe();
    if (!shared_) pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  void raised() { raised_ = true; }

 private:
  sigset_t old_{};
  bool shared_ = false, was_pending_ = false, raised_ = false;
};

// The child, until it is reaped: killed with its group and waited for on any way out.
class Child {
 public:
  explicit Child(pid_t pid) : pid_(pid) {
    const std::lock_guard lock(running_mutex);
    running.insert(pid_);
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    if (!reaped()) {
      end_group();
      wait(0);
    }
  }
  bool reaped() const { return reaped_; }
  // Ends the program and every process of its group.
  void end_group() const {
    killpg(pid_, SIGKILL);
    if (!reaped_) kill(pid_, SIGKILL);  // in case it left the group
  }
  // waitpid with `options` (0 or WNOHANG); true once reaped. A blocking wait follows a
  // SIGKILL (its pid stays the child's until it is reaped), so the group leaves the set first.
  bool wait(int options) {
    if (reaped_) return true;
    int status = 0;
    rusage usage{};
    pid_t got;
    {
      std::unique_lock lock(running_mutex);
      if (options == 0) {
        running.erase(pid_);
        lock.unlock();
      }
      while ((got = wait4(pid_, &status, options, &usage)) < 0 && errno == EINTR) {
      }
      if (got == pid_ && lock.owns_lock()) running.erase(pid_);
    }
    if (got != pid_) return false;
    reaped_ = true;
    status_ = status;
    cpu_ = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    return true;
  }
  int status() const { return status_; }
  double cpu_seconds() const { return cpu_; }
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_;
  bool reaped_ = false;
  int status_ = 0;
  double cpu_ = 0.0;
};

std::string error_text(int error) { return std::generic_category().message(error); }

// The CPU clock of process `pid`: the run time of its threads summed, to the nanosecond, read
// in one system call (a persistent program's cost per exchange, where its rusage comes only
// when it is reaped and /proc's stat counts in 10 ms ticks). Its sum is the first field of each
// /proc/<pid>/task/<tid>/schedstat, which was read instead: a directory and a file per thread,
// some 20 system calls and 30,000 instructions an exchange, a tenth of a persistent sweep's work
// through a program that answers at once (issue 46). The clock also keeps the time of a thread
// that ended in the exchange, which the files had lost. None where the system has none.
std::optional<clockid_t> process_cpu_clock(pid_t pid) {
  clockid_t clock{};
  if (clock_getcpuclockid(pid, &clock) != 0) return std::nullopt;
  return clock;
}

// Seconds on `clock` (process_cpu_clock); NaN where it cannot be read.
double cpu_clock_seconds(std::optional<clockid_t> clock) {
  timespec t{};
  if (!clock || clock_gettime(*clock, &t) != 0) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Starts argv with `in` as its stdin, `out` as stdout, `err` as stderr, in a process group of
// its own, with the signal mask and the dispositions a program expects (poundbench's own may
// block or ignore signals); returns the pid, or -1 with `error` set.
pid_t spawn(const std::vector<std::string>& argv, const Fd& in, const Fd& out, const Fd& err, int& error) {
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attr;
  posix_spawn_file_actions_init(&actions);
  posix_spawnattr_init(&attr);
  posix_spawn_file_actions_adddup2(&actions, in.get(), 0);
  posix_spawn_file_actions_adddup2(&actions, out.get(), 1);
  posix_spawn_file_actions_adddup2(&actions, err.get(), 2);
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 34))
  posix_spawn_file_actions_addclosefrom_np(&actions, 3);
#endif
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int sig : {SIGPIPE, SIGINT, SIGTERM, SIGQUIT, SIGHUP}) sigaddset(&defaults, sig);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETPGROUP);

  std::vector<char*> args;
  for (const std::string& word : argv) args.push_back(const_cast<char*>(word.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  error = posix_spawnp(&pid, args[0], &actions, &attr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  return error == 0 ? pid : -1;
}

// Reads what is there; false at end of file or on an error.
bool read_some(const Fd& fd, std::string& into) {
  char buffer[kChunk];
  const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
  if (n > 0) {
    into.append(buffer, static_cast<std::size_t>(n));
    return true;
  }
  return n < 0 && (errno == EAGAIN || errno == EINTR);
}

// Reads what is there now, without waiting: true once the pipe is empty (EAGAIN: nothing
// came, which is no progress to wait on) or `most` bytes have been read; false at its end or
// on an error. The bound is for a writer that keeps the pipe full (a process the program left
// behind, writing on): it cannot hold the caller.
bool read_available(const Fd& fd, std::string& into, std::size_t most) {
  const std::size_t limit = into.size() + most;
  char buffer[kChunk];
  while (into.size() < limit) {
    const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
    if (n > 0) {
      into.append(buffer, static_cast<std::size_t>(n));
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      return n < 0 && errno == EAGAIN;
    }
  }
  return true;
}

// The bytes written to a pipe that its reader has not read yet (FIONREAD, which Linux answers
// on either end); 0 where it cannot say.
std::size_t unread_bytes(const Fd& write_end) {
  int n = 0;
  return ioctl(write_end.get(), FIONREAD, &n) == 0 && n > 0 ? static_cast<std::size_t>(n) : 0;
}

}  // namespace

std::string last_lines(std::string_view text, int lines) {
  std::vector<std::string_view> kept;  // from the end
  while (!text.empty() && static_cast<int>(kept.size()) < lines) {
    const std::size_t cut = text.rfind('\n');
    std::string_view line = cut == std::string_view::npos ? text : text.substr(cut + 1);
    text = cut == std::string_view::npos ? std::string_view() : text.substr(0, cut);
    while (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (!line.empty()) kept.push_back(line);
  }
  std::string out;
  for (auto line = kept.rbegin(); line != kept.rend(); ++line) out += (out.empty() ? "" : " | ") + std::string(*line);
  return out;
}

void end_running_programs() {
  const std::lock_guard lock(running_mutex);
  for (pid_t group : running) killpg(group, SIGKILL);
}

ProgramRun run_program(const std::vector<std::string>& argv, std::string_view input, const ProgramLimits& limits) {
  ProgramRun run;
  if (argv.empty()) {
    run.spawn_error = "no program";
    return run;
  }
  Fd in_read, in_write, out_read, out_write, err_read, err_write;
  if (!make_pipe(in_read, in_write) || !make_pipe(out_read, out_write) || !make_pipe(err_read, err_write)) {
    run.spawn_error = "cannot make a pipe: " + error_text(errno);
    return run;
  }
  SigpipeBlock sigpipe;  // before the first write; the child gets an empty mask
  const Clock::time_point start = Clock::now();
  int error = 0;
  const pid_t pid = spawn(argv, in_read, out_write, err_write, error);
  if (pid < 0) {
    run.spawn_error = argv[0] + ": " + error_text(error);
    return run;
  }
  Child child(pid);
  in_read.reset();  // the child's ends: EOF comes once the program's side closes
  out_write.reset();
  err_write.reset();
  set_nonblocking(in_write);
  set_nonblocking(out_read);
  set_nonblocking(err_read);

  std::string err;
  std::size_t written = 0;
  if (input.empty()) in_write.reset();
  Clock::time_point exited_at{};
  double nap = kFirstNap;
  const auto end = [&](bool& why) {
    why = true;
    child.end_group();
  };
  for (;;) {
    if (limits.stop && limits.stop->load(std::memory_order_relaxed)) {
      end(run.stopped);
      break;
    }
    const double elapsed = seconds_since(start);
    if (limits.kill_after > 0.0 && elapsed > limits.kill_after) {
      end(run.timed_out);
      break;
    }
    if (!child.reaped() && child.wait(WNOHANG)) exited_at = Clock::now();
    if (child.reaped() && !out_read.open() && !err_read.open()) break;
    if (child.reaped() && seconds_since(exited_at) > kDrainAfterExit) {
      child.end_group();  // what it left behind holds the pipes
      break;
    }

    pollfd fds[3];
    nfds_t n = 0;
    if (in_write.open()) fds[n++] = {in_write.get(), POLLOUT, 0};
    if (out_read.open()) fds[n++] = {out_read.get(), POLLIN, 0};
    if (err_read.open()) fds[n++] = {err_read.get(), POLLIN, 0};
    double wait = n ? kPollSeconds : std::exchange(nap, std::min(2.0 * nap, kPollSeconds));
    if (limits.kill_after > 0.0) wait = std::clamp(limits.kill_after - elapsed + 1e-4, 1e-4, wait);
    const timespec timeout{static_cast<time_t>(wait), static_cast<long>((wait - std::floor(wait)) * 1e9)};
    if (ppoll(n ? fds : nullptr, n, &timeout, nullptr) < 0) {
      if (errno == EINTR) continue;
      end(run.stopped);  // cannot wait for it: treated as a stop, which the caller reports
      break;
    }
    for (nfds_t k = 0; k < n; ++k) {
      if (!fds[k].revents) continue;
      if (fds[k].fd == in_write.get()) {
        const std::size_t size = std::min(kChunk, input.size() - written);
        const ssize_t w = ::write(in_write.get(), input.data() + written, size);
        if (w > 0) written += static_cast<std::size_t>(w);
        if (w < 0 && errno == EPIPE) {
          sigpipe.raised();
          run.input_refused = true;
        }
        if (written == input.size() || (w < 0 && errno != EAGAIN && errno != EINTR)) in_write.reset();
      } else if (fds[k].fd == out_read.get()) {
        if (!read_some(out_read, run.out)) out_read.reset();
      } else if (fds[k].fd == err_read.get()) {
        if (!read_some(err_read, err)) err_read.reset();
        if (err.size() > 2 * kErrTail) err.erase(0, err.size() - kErrTail);
      }
    }
    if (limits.max_output > 0 && run.out.size() > limits.max_output) {
      end(run.output_cut);
      break;
    }
  }
  child.wait(0);
  run.seconds = seconds_since(start);
  run.cpu_seconds = child.cpu_seconds();
  if (WIFEXITED(child.status())) {
    run.exited = true;
    run.exit_code = WEXITSTATUS(child.status());
  } else if (WIFSIGNALED(child.status())) {
    run.signal = WTERMSIG(child.status());
  }
  if (err.size() > kErrTail) err.erase(0, err.size() - kErrTail);
  run.err_tail = std::move(err);
  return run;
}

}  // namespace pb::programs

namespace pb::programs {

namespace {

// Waits kDrainAfterExit at most for `child` to exit by itself, in naps from kFirstNap: true
// once it is reaped.
bool wait_for_exit(Child& child) {
  const Clock::time_point from = Clock::now();
  double nap = kFirstNap;
  while (!child.wait(WNOHANG)) {
    if (seconds_since(from) >= kDrainAfterExit) return false;
    const timespec pause{0, static_cast<long>(nap * 1e9)};
    nanosleep(&pause, nullptr);
    nap = std::min(2.0 * nap, kPollSeconds);
  }
  return true;
}

// A program kept running between points: its pipes, what it wrote past the last line read, the
// tail of its stderr. Owned by one thread (a sweep's worker), so nothing here is locked.
class Session {
 public:
  explicit Session(std::vector<std::string> argv) : argv_(std::move(argv)) {}
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ~Session() { close(); }
  const std::vector<std::string>& argv() const { return argv_; }

  ProgramRun exchange(std::string_view line, const ProgramLimits& limits, double& startup) {
    ProgramRun run;
    startup = std::numeric_limits<double>::quiet_NaN();
    const Clock::time_point start = Clock::now();
    SigpipeBlock sigpipe;
    err_.clear();
    if (!child_) {
      if (!start_program(run, limits, start, sigpipe)) return run;
      startup = seconds_since(start);
    }
    if (!waiting_for_case(run)) return run;
    std::string input(line);
    input += '\n';
    const double cpu_before = cpu_clock_seconds(cpu_clock_);
    if (converse(input, run, limits, start, sigpipe)) {
      run.exited = true;  // answered, as a program of run_program that exits with 0 (it goes on running)
      run.exit_code = 0;
      run.cpu_seconds = cpu_clock_seconds(cpu_clock_) - cpu_before;
    }
    run.seconds = seconds_since(start);
    return run;
  }

  // Ends the program: its stdin closed (a program that reads to its end exits), kDrainAfterExit
  // to exit, then SIGKILL to its group.
  void close() {
    if (!child_) return;
    in_.reset();
    wait_for_exit(*child_);
    child_.reset();  // its destructor ends and reaps what is left
    out_.reset();
    err_read_.reset();
    pending_.clear();
  }

 private:
  bool spawn_program(ProgramRun& run) {
    Fd in_read, out_write, err_write;
    if (!make_pipe(in_read, in_) || !make_pipe(out_, out_write) || !make_pipe(err_read_, err_write)) {
      run.spawn_error = "cannot make a pipe: " + error_text(errno);
      return false;
    }
    int error = 0;
    const pid_t pid = spawn(argv_, in_read, out_write, err_write, error);
    if (pid < 0) {
      run.spawn_error = argv_[0] + ": " + error_text(error);
      in_.reset();
      out_.reset();
      err_read_.reset();
      return false;
    }
    child_ = std::make_unique<Child>(pid);
    cpu_clock_ = process_cpu_clock(pid);
    set_nonblocking(in_);
    set_nonblocking(out_);
    set_nonblocking(err_read_);
    return true;
  }

  // Starts the program and reads its ready line, within the point's limit (a start that hangs
  // is this point's time-limit): true, or false with run saying why.
  bool start_program(ProgramRun& run, const ProgramLimits& limits, Clock::time_point start, SigpipeBlock& sigpipe) {
    if (!spawn_program(run) || !converse({}, run, limits, start, sigpipe)) return false;
    if (std::string bad = ready_line_problem(run.out); !bad.empty()) {
      end(run);
      run.spawn_error = argv_[0] + ": " + bad;
      return false;
    }
    run.out.clear();
    return true;
  }

  // Before a case is sent, the program must be waiting for it: nothing on its stdout (a line
  // there, such as a second answer to the last case written late, is no answer to this case,
  // and would be taken for it), and still running. Else it is ended, run says why: false.
  bool waiting_for_case(ProgramRun& run) {
    const bool open = read_available(out_, pending_, kChunk);
    if (!pending_.empty()) {
      const std::string_view stray = std::string_view(pending_).substr(0, pending_.find('\n'));
      run.protocol_error = "the program wrote '" + clip(stray) +
                           "' to stdout before this case was sent (persistent mode: one answer line per case line)";
      end(run);
      return false;
    }
    if (!open) out_.reset();
    if (!open || child_->wait(WNOHANG)) return ended_by_itself(run);
    return true;
  }

  // Writes `input`, then reads until a whole line is there (into run.out, without its end):
  // true. Else the program is ended and run says why: false.
  bool converse(std::string_view input, ProgramRun& run, const ProgramLimits& limits, Clock::time_point start,
                SigpipeBlock& sigpipe) {
    std::size_t written = 0;
    for (;;) {
      if (const std::size_t end_of_line = pending_.find('\n');
          end_of_line != std::string::npos && written == input.size())
        return take_line(input, end_of_line, run);
      if (limits.stop && limits.stop->load(std::memory_order_relaxed)) return end(run, run.stopped);
      const double elapsed = seconds_since(start);
      if (limits.kill_after > 0.0 && elapsed > limits.kill_after) return end(run, run.timed_out);
      if (limits.max_output > 0 && pending_.size() > limits.max_output) return end(run, run.output_cut);
      if (!out_.open()) return ended_by_itself(run);
      if (child_->wait(WNOHANG)) {
        // It has exited: what it wrote is in the pipe now. A process it left behind may hold
        // the pipe open for as long as it likes; it is not the program, and is not waited for.
        if (!read_available(out_, pending_, limits.max_output > 0 ? limits.max_output : kChunk)) out_.reset();
        if (pending_.find('\n') != std::string::npos && written == input.size()) continue;
        return ended_by_itself(run);
      }

      // The case is written before any poll for room: the pipe takes a line of a case at once
      // nearly always (it holds 64 KiB), and a poll for it, with the look at the child that
      // came with the next turn of this loop, was two system calls a point.
      if (written < input.size()) write_some(input, written, run, sigpipe);
      pollfd fds[3];
      nfds_t n = 0;
      const bool writing = written < input.size();
      if (writing) fds[n++] = {in_.get(), POLLOUT, 0};
      fds[n++] = {out_.get(), POLLIN, 0};
      if (err_read_.open()) fds[n++] = {err_read_.get(), POLLIN, 0};
      double wait = kPollSeconds;
      if (limits.kill_after > 0.0) wait = std::clamp(limits.kill_after - elapsed + 1e-4, 1e-4, wait);
      const timespec timeout{0, static_cast<long>(wait * 1e9)};
      if (ppoll(fds, n, &timeout, nullptr) < 0) {
        if (errno == EINTR) continue;
        return end(run, run.stopped);
      }
      for (nfds_t k = 0; k < n; ++k) {
        if (!fds[k].revents) continue;
        if (writing && fds[k].fd == in_.get()) {
          write_some(input, written, run, sigpipe);
        } else if (fds[k].fd == out_.get()) {
          if (!read_some(out_, pending_)) out_.reset();
        } else if (fds[k].fd == err_read_.get()) {
          if (!read_some(err_read_, err_)) err_read_.reset();
          if (err_.size() > 2 * kErrTail) err_.erase(0, err_.size() - kErrTail);
        }
      }
    }
  }

  // Writes what the pipe takes of `input` past `written` (its end does not block).
  void write_some(std::string_view input, std::size_t& written, ProgramRun& run, SigpipeBlock& sigpipe) {
    const ssize_t w = ::write(in_.get(), input.data() + written, std::min(kChunk, input.size() - written));
    if (w > 0) written += static_cast<std::size_t>(w);
    if (w < 0 && errno == EPIPE) sigpipe.raised();
    // A program that closed its stdin will not read the case: its answer (or end) says why.
    if (w < 0 && errno != EAGAIN && errno != EINTR) {
      run.input_refused = true;
      written = input.size();
    }
  }

  // The line that ends at `end_of_line` of pending_, once all of `input` was written: the answer
  // (true), unless the program wrote it while every byte of the case still sat unread in its
  // stdin. A program cannot answer a case it has not read: that line was written before, and
  // is ended as a protocol_error (false).
  bool take_line(std::string_view input, std::size_t end_of_line, ProgramRun& run) {
    run.out.assign(pending_, 0, end_of_line);
    pending_.erase(0, end_of_line + 1);
    if (input.empty() || run.input_refused || unread_bytes(in_) < input.size()) return true;
    run.protocol_error = "the program wrote '" + clip(run.out) +
                         "' before it read this case: not its answer (persistent mode: one answer line per case line)";
    run.out.clear();
    end(run);
    return false;
  }

  // Ends the program for the reason `why` (a flag of run): false, for converse to return.
  bool end(ProgramRun& run, bool& why) {
    why = true;
    end(run);
    return false;
  }
  void end(ProgramRun& run) {
    if (child_) {
      child_->end_group();
      child_->wait(0);
    }
    finish(run);
  }
  // It exited, or is about to (its stdout ended), without an answer: given kDrainAfterExit,
  // then ended. What it left in its group (a child still holding its stdout) is ended with it.
  bool ended_by_itself(ProgramRun& run) {
    if (!wait_for_exit(*child_) || out_.open()) {
      child_->end_group();
      child_->wait(0);
    }
    const int status = child_->status();
    run.unanswered = true;
    run.exited = WIFEXITED(status);
    run.exit_code = run.exited ? WEXITSTATUS(status) : -1;
    run.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    finish(run);
    return false;
  }
  // What stderr holds now read into the tail, without waiting for its end (a process of
  // another session may hold it open for good), and the program forgotten: the next exchange
  // starts it again.
  void finish(ProgramRun& run) {
    if (err_read_.open()) read_available(err_read_, err_, 2 * kErrTail);
    if (err_.size() > kErrTail) err_.erase(0, err_.size() - kErrTail);
    run.err_tail = err_;
    child_.reset();
    in_.reset();
    out_.reset();
    err_read_.reset();
    pending_.clear();
  }

  std::vector<std::string> argv_;
  std::unique_ptr<Child> child_;
  std::optional<clockid_t> cpu_clock_;  // the child's (process_cpu_clock)
  Fd in_, out_, err_read_;
  std::string pending_, err_;
};

// The calling thread's sessions, one per command (a settings list may run several).
thread_local std::vector<std::unique_ptr<Session>> sessions;

}  // namespace

ProgramRun exchange(const std::vector<std::string>& argv, std::string_view line, const ProgramLimits& limits,
                    double& startup_seconds) {
  auto found = std::find_if(sessions.begin(), sessions.end(), [&](const auto& s) { return s->argv() == argv; });
  if (found == sessions.end()) {
    if (argv.empty()) {
      ProgramRun run;
      run.spawn_error = "no program";
      startup_seconds = std::numeric_limits<double>::quiet_NaN();
      return run;
    }
    sessions.push_back(std::make_unique<Session>(argv));
    found = std::prev(sessions.end());
  }
  return (*found)->exchange(line, limits, startup_seconds);
}

void end_thread_sessions() { sessions.clear(); }

ThreadSessionsEnd::ThreadSessionsEnd() { ++thread_sigpipe.depth; }

ThreadSessionsEnd::~ThreadSessionsEnd() {
  end_thread_sessions();
  if (--thread_sigpipe.depth > 0 || !thread_sigpipe.blocked) return;
  pthread_sigmask(SIG_SETMASK, &thread_sigpipe.old, nullptr);
  thread_sigpipe.blocked = false;
}

}  // namespace pb::programs
