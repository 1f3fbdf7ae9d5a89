#include "output/output_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <iostream>
#include <map>
#include <streambuf>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "cases/text.hpp"
#include "frontend/errors.hpp"

namespace pb::app {

namespace fs = std::filesystem;

namespace {

// A device or a pipe (/dev/null, /dev/stdout, a FIFO): written in place, since renaming a
// temporary onto it would replace it with a regular file.
bool is_special(const fs::path& file) {
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  return !ec && fs::exists(st) && !fs::is_regular_file(st) && !fs::is_directory(st);
}

// A device or a pipe opened for writing, waiting at most kReaderWait for a FIFO's reader
// (open would wait for ever: a FIFO nobody reads hung the command after its whole run), then
// made blocking again for the write; -1 and errno on failure (ENXIO: no reader came).
constexpr auto kReaderWait = std::chrono::seconds(2);

int open_special(const fs::path& file) {
  const auto give_up = std::chrono::steady_clock::now() + kReaderWait;
  int fd = -1;
  while ((fd = ::open(file.c_str(), O_WRONLY | O_TRUNC | O_NONBLOCK | O_CLOEXEC)) < 0 && errno == ENXIO &&
         std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (fd < 0) return fd;
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0) {
    const int error = errno;
    ::close(fd);
    errno = error;
    return -1;
  }
  return fd;
}

// The FIFOs check_output_target opened, kept open until write_atomically writes them: a
// probe closed before the write would end a reader such as `cat` at its EOF. (The command
// line is one thread: no lock.)
std::map<std::string, int>& held_fifos() {
  static std::map<std::string, int> held;
  return held;
}

bool a_fifo(const fs::path& file) {
  std::error_code ec;
  return fs::is_fifo(fs::status(file, ec));
}

std::string cannot_open(int error) {
  return error == ENXIO ? "cannot open: a FIFO that nobody read within 2 s"
                        : std::string("cannot open: ") + std::strerror(error);
}

// access() grants root everything and knows nothing of read-only or virtual file systems
// (/proc, /sys): only creating a file tells. Creates the temporary that write_atomically
// writes through, and removes it again unless it was there before.
void probe_temporary(const fs::path& file, const std::string& prefix) {
  const fs::path tmp = file.string() + ".tmp";
  std::error_code ec;
  const bool existed = fs::exists(tmp, ec);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int error = errno;
    throw BadInput(prefix + "cannot create: " + std::strerror(error));
  }
  ::close(fd);
  if (!existed) fs::remove(tmp, ec);
}

// An ostream's buffer on a file descriptor that keeps the errno of a failed write, which
// std::ofstream does not promise to: the message of a failed output names the reason.
class FdBuffer : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    const char* at = pbase();
    while (error_ == 0 && at < pptr()) {
      const ssize_t n = ::write(fd_, at, static_cast<std::size_t>(pptr() - at));
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) error_ = errno;
      else at += n;
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return error_ == 0;
  }

  int fd_;
  int error_ = 0;
  std::array<char, 1 << 16> buffer_{};
};

// Runs `write` on an ostream over `fd`, then (sync) fsyncs and (close) closes it; returns
// the errno of the first failure, 0 if none.
int write_fd(int fd, const std::function<void(std::ostream&)>& write, bool sync, bool close = true) {
  FdBuffer buffer(fd);
  std::ostream out(&buffer);
  try {
    write(out);
  } catch (...) {
    if (close) ::close(fd);
    throw;
  }
  out.flush();
  int error = buffer.error();
  if (error == 0 && !out) error = EIO;  // the stream failed without a write failing
  if (error == 0 && sync && ::fsync(fd) != 0) error = errno;
  if (close && ::close(fd) != 0 && error == 0) error = errno;
  return error;
}

}  // namespace

void check_output_target(const fs::path& file, std::string_view flag) {
  const std::string prefix = std::string(flag) + ": " + file.string() + ": ";
  std::error_code ec;
  if (file.empty()) throw BadInput(std::string(flag) + ": empty file name");
  if (fs::is_directory(file, ec)) throw BadInput(prefix + "is a directory");
  if (is_special(file)) {
    if (::access(file.c_str(), W_OK) != 0) throw BadInput(prefix + "is not writable");
    // A FIFO nobody reads is refused now, not after the run (the open waits 2 s for a reader).
    if (a_fifo(file) && !held_fifos().contains(file.string())) {
      const int fd = open_special(file);
      if (fd < 0) throw BadInput(prefix + cannot_open(errno));
      held_fifos()[file.string()] = fd;
    }
    return;
  }
  fs::path dir = file.parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir, ec)) throw BadInput(prefix + "directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0) throw BadInput(prefix + "directory " + dir.string() + " is not writable");
  if (fs::exists(file, ec) && ::access(file.c_str(), W_OK) != 0) throw BadInput(prefix + "is not writable");
  probe_temporary(file, prefix);
}

void check_sweep_output(const fs::path& file, std::string_view flag) {
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  if (!ec && fs::exists(st) && !fs::is_regular_file(st) && !fs::is_directory(st))
    throw BadInput(std::string(flag) + ": " + file.string() +
                   ": not a regular file (a device or a pipe): a sweep writes its output through a temporary file "
                   "and a partial file next to it; leave out " + std::string(flag) + " to write to stdout");
  check_output_target(file, flag);
}

namespace {

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  const fs::path x = fs::weakly_canonical(fs::absolute(a, ec), ec), y = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return !x.empty() && x == y;
}

}  // namespace

void check_outputs_apart(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs,
                         std::string_view partial, std::string_view lock) {
  // What goes on the disk, by whose it is: each output and its temporary, then the sweep's
  // partial file (and its temporary) and lock, which are no output's alone (owner -1).
  struct Written {
    NamedFile file;
    int owner;
  };
  std::vector<Written> written;
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const NamedFile& out = outputs[i];
    if (out.path.empty()) continue;
    written.push_back({out, static_cast<int>(i)});
    written.push_back({{out.name + "'s temporary", out.path.string() + ".tmp"}, static_cast<int>(i)});
  }
  if (!partial.empty()) {
    written.push_back({{"the partial file", std::string(partial)}, -1});
    written.push_back({{"the partial file's temporary", std::string(partial) + ".tmp"}, -1});
  }
  if (!lock.empty()) written.push_back({{"the lock file", std::string(lock)}, -1});
  const auto named = [](const NamedFile& f) { return f.name + " " + clip(f.path.string(), kMaxEchoedReason); };
  for (const NamedFile& in : inputs)
    for (const Written& w : written)
      if (same_file(w.file.path, in.path))
        throw BadInput(in.name + ": " + clip(in.path.string(), kMaxEchoedReason) + ": " +
                       (w.owner >= 0 ? "would be overwritten by " : "would be overwritten as ") + named(w.file) +
                       " (an output must not be an input)");
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].path.empty()) continue;
    for (const Written& w : written)
      if (w.owner != static_cast<int>(i) && same_file(outputs[i].path, w.file.path))
        throw BadInput(outputs[i].name + ": " + clip(outputs[i].path.string(), kMaxEchoedReason) + ": is also " +
                       named(w.file) + " (each output needs a file of its own)");
  }
}

std::vector<NamedFile> record_files(const CaseList& cases) {
  std::vector<NamedFile> files;
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (const Case c = cases[i]; !c.record.empty() && (files.empty() || files.back().path != c.record) &&
        std::none_of(files.begin(), files.end(), [&](const NamedFile& f) { return f.path == c.record; }))
      files.push_back({"record", c.record});
  return files;
}

void write_atomically(const fs::path& file, const std::function<void(std::ostream&)>& write) {
  if (is_special(file)) {
    int fd = -1;
    if (const auto held = held_fifos().find(file.string()); held != held_fifos().end()) {
      fd = held->second;
      held_fifos().erase(held);
    } else {
      fd = open_special(file);
    }
    if (fd < 0) throw std::runtime_error(file.string() + ": " + cannot_open(errno));
    const int error = write_fd(fd, write, false);
    if (error != 0) throw std::runtime_error(file.string() + ": write failed: " + std::strerror(error));
    return;
  }
  const fs::path tmp = file.string() + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(tmp.string() + ": cannot create: " + std::strerror(errno));
  // fsync before the rename: otherwise a power cut can leave the new name on an empty file.
  int error = 0;
  try {
    error = write_fd(fd, write, true);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  if (error != 0) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw std::runtime_error(tmp.string() + ": write failed: " + std::strerror(error));
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error(file.string() + ": cannot rename " + tmp.string() + " into place: " + ec.message());
  }
}

void write_to_stdout(const std::function<void(std::ostream&)>& write) {
  std::cout.flush();  // nothing of the sweeps' is in it; keeps the order should that change
  const int error = write_fd(STDOUT_FILENO, write, false, false);
  if (error != 0) throw std::runtime_error(std::string("stdout: write failed: ") + std::strerror(error));
}

BatchedFile::BatchedFile(const fs::path& file, Mode mode, Duration max_delay)
    : path_(file), file_(std::fopen(file.c_str(), mode == Mode::append ? "a" : "w")), max_delay_(max_delay) {
  if (!file_) throw std::runtime_error(file.string() + ": cannot create: " + std::strerror(errno));
}

BatchedFile::~BatchedFile() {
  if (!file_) return;
  try {
    write_batch();
  } catch (const std::exception&) {
    // Unwinding (a sweep that failed), or a close() that was never reached: nothing to report to.
  }
  std::fclose(file_);
}

void BatchedFile::add_line(std::string_view line) {
  if (!error_.empty()) throw std::runtime_error(error_);
  if (batch_.empty()) oldest_ = std::chrono::steady_clock::now();
  batch_.append(line);
  batch_.push_back('\n');
  write_due();
}

void BatchedFile::write_due() {
  if (!error_.empty()) throw std::runtime_error(error_);
  if (batch_.empty()) return;
  if (batch_.size() >= kMaxBatchBytes || std::chrono::steady_clock::now() - oldest_ >= max_delay_) write_batch();
}

void BatchedFile::flush() { write_batch(); }

void BatchedFile::write_batch() {
  if (!error_.empty()) throw std::runtime_error(error_);
  if (!file_) throw std::runtime_error(path_.string() + ": write after close");
  if (batch_.empty()) return;
  if (std::fwrite(batch_.data(), 1, batch_.size(), file_) != batch_.size() || std::fflush(file_) != 0) {
    error_ = path_.string() + ": write failed: " + std::strerror(errno);
    throw std::runtime_error(error_);
  }
  batch_.clear();
}

void BatchedFile::close() {
  if (!file_) return;
  write_batch();
  const int closed = std::fclose(file_);
  file_ = nullptr;
  if (closed != 0) throw std::runtime_error(path_.string() + ": close failed: " + std::strerror(errno));
}

}  // namespace pb::app
