#include "tests/fuzz/child.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <typeinfo>

extern char** environ;

namespace pb::fuzz {

namespace {

using Clock = std::chrono::steady_clock;

std::size_t resident_bytes(pid_t pid) {
  std::ifstream statm("/proc/" + std::to_string(pid) + "/statm");
  std::size_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
}

// The CPU seconds `pid` has spent, with those of its children it has waited for (proc(5):
// utime, stime, cutime, cstime, the 14th to 17th fields, after the command's parentheses).
double cpu_seconds(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const std::size_t close = text.rfind(')');
  if (close == std::string::npos) return 0;
  std::istringstream fields(text.substr(close + 2));
  std::string field;
  double ticks = 0;
  for (int i = 3; i <= 17 && fields >> field; ++i)
    if (i >= 14) ticks += std::strtod(field.c_str(), nullptr);
  return ticks / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

void keep(std::string& into, std::size_t& size, const char* data, std::size_t n) {
  size += n;
  if (into.size() < ChildOutcome::kKeep) into.append(data, std::min(n, ChildOutcome::kKeep - into.size()));
}

// Forks; in the child, `in_child` runs with stdout/stderr on pipes and must not return.
template <class InChild>
ChildOutcome supervise(InChild in_child, const ChildLimits& limits) {
  int out_pipe[2], err_pipe[2];
  if (::pipe(out_pipe) != 0 || ::pipe(err_pipe) != 0) throw std::runtime_error("pipe failed");
  std::fflush(nullptr);  // else the child inherits, and would print, the parent's pending output
  const auto start = Clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    ::dup2(out_pipe[1], 1);
    ::dup2(err_pipe[1], 2);
    for (int fd : {out_pipe[0], out_pipe[1], err_pipe[0], err_pipe[1]}) ::close(fd);
    in_child();
    ::_exit(127);
  }
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);

  ChildOutcome o;
  pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  int open = 2;
  bool killed = false;
  char buffer[65536];
  // Read both pipes until the child closes them (it exits), watching its time and memory.
  while (open > 0) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    if (!killed && cpu_seconds(pid) > limits.seconds) {
      o.timed_out = killed = true;
      ::kill(pid, SIGKILL);
    } else if (!killed && elapsed > limits.wall_limit()) {
      o.timed_out = o.blocked = killed = true;
      ::kill(pid, SIGKILL);
    } else if (!killed && resident_bytes(pid) > limits.max_rss_bytes) {
      o.over_memory = killed = true;
      ::kill(pid, SIGKILL);
    }
    if (::poll(fds, 2, 20) < 0 && errno != EINTR) break;
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t n = ::read(fds[i].fd, buffer, sizeof buffer);
      if (n > 0) {
        keep(i == 0 ? o.out : o.err, i == 0 ? o.out_size : o.err_size, buffer, static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        ::close(fds[i].fd);
        fds[i].fd = -1;
        --open;
      }
    }
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  o.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  o.exited = WIFEXITED(status);
  o.exit_code = o.exited ? WEXITSTATUS(status) : -1;
  o.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  return o;
}

}  // namespace

std::string ChildOutcome::describe() const {
  char seconds_text[32];
  std::snprintf(seconds_text, sizeof seconds_text, "%.1f", seconds);
  if (blocked) return std::string("hang: blocked, no exit within ") + seconds_text + " s (killed)";
  if (timed_out) return std::string("hang: past its CPU limit after ") + seconds_text + " s (killed)";
  if (over_memory) return "memory: over the limit after " + std::string(seconds_text) + " s (killed)";
  if (const std::string line = sanitizer_line(err); !line.empty()) return "sanitizer: " + line;
  if (!exited) return "crash: signal " + std::to_string(signal) + " (" + ::strsignal(signal) + ")";
  return "exit " + std::to_string(exit_code);
}

ChildOutcome run_in_child(const std::function<void()>& body, const ChildLimits& limits) {
  return supervise(
      [&] {
        body();
        // Every stream, not just `stdout`: where the Simbody engine is linked, `stdout` is
        // its filter (solvers/simbody/quiet_stdout.hpp), which hands bytes to the original
        // FILE's buffer, and _exit flushes nothing.
        std::fflush(nullptr);
        ::_exit(0);
      },
      limits);
}

ChildOutcome run_program(const std::string& program, const std::vector<std::string>& args,
                         const std::filesystem::path& dir, const ChildLimits& limits, const ProgramInput& input) {
  // Built before the fork: the child only calls async-signal-safe functions.
  std::vector<char*> argv;
  std::vector<std::string> words = {program};
  words.insert(words.end(), args.begin(), args.end());
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::vector<std::string> variables = input.environment;
  for (char** e = environ; *e; ++e) variables.emplace_back(*e);  // the added ones first: they win
  std::vector<char*> envp;
  for (std::string& v : variables) envp.push_back(v.data());
  envp.push_back(nullptr);
  const std::string where = dir.string();
  // The stdin's file: in the temporary directory, one per process and call (campaigns run in
  // parallel, and `dir` may be the source tree).
  static std::atomic<int> calls{0};
  std::string stdin_file = "/dev/null";
  if (!input.stdin_text.empty()) {
    stdin_file = (std::filesystem::temp_directory_path() /
                  ("poundbench-fuzz-stdin-" + std::to_string(::getpid()) + "-" + std::to_string(calls++)))
                     .string();
    std::ofstream(stdin_file, std::ios::binary) << input.stdin_text;
  }
  const ChildOutcome o = supervise(
      [&] {
        if (::chdir(where.c_str()) != 0) ::_exit(126);
        const int in = ::open(stdin_file.c_str(), O_RDONLY);
        if (in < 0 || ::dup2(in, 0) < 0) ::_exit(126);
        ::close(in);
        ::execve(program.c_str(), argv.data(), envp.data());
        ::_exit(127);
      },
      limits);
  if (!input.stdin_text.empty()) std::filesystem::remove(stdin_file);
  return o;
}

std::string sanitizer_line(const std::string& err) {
  for (const char* marker : {"ERROR: AddressSanitizer", "ERROR: LeakSanitizer", "runtime error:"}) {
    const std::size_t at = err.find(marker);
    if (at == std::string::npos) continue;
    const std::size_t begin = err.rfind('\n', at);
    const std::size_t end = err.find('\n', at);
    return err.substr(begin == std::string::npos ? 0 : begin + 1,
                      (end == std::string::npos ? err.size() : end) - (begin == std::string::npos ? 0 : begin + 1));
  }
  return {};
}

ChildOutcome report_in_child(const std::function<std::string()>& body, const ChildLimits& limits) {
  return run_in_child(
      [&] {
        std::string report;
        try {
          report = body();
        } catch (const std::exception& e) {
          report = std::string("EXC ") + typeid(e).name() + ": " + e.what();
        } catch (...) {
          report = "EXC (not a std::exception)";
        }
        std::fwrite(report.data(), 1, report.size(), stdout);
      },
      limits);
}

}  // namespace pb::fuzz
