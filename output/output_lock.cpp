#include "output/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <utility>

#include "frontend/errors.hpp"

namespace pb::app {

namespace {

// The pid the holder wrote, or "unknown" (it may not have written it yet).
std::string holder_of(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string pid(text, n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos ? "unknown" : pid;
}

// Whether `fd` is still the file at `path` (its holder may have removed it meanwhile).
bool still_there(int fd, const std::string& path) {
  struct stat open_file {}, named {};
  return ::fstat(fd, &open_file) == 0 && ::stat(path.c_str(), &named) == 0 && open_file.st_dev == named.st_dev &&
         open_file.st_ino == named.st_ino;
}

}  // namespace

std::string lock_file_name(const std::string& out, std::string_view command) {
  return out.empty() ? "poundbench-" + std::string(command) + ".lock" : out + ".lock";
}

OutputLock::OutputLock(std::string lock_file, std::string_view what) : path_(std::move(lock_file)) {
  const std::string prefix = std::string(what) + ": ";
  // A few rounds at most: each one that fails lost a race with a holder removing its file.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw BadInput(prefix + "cannot create the lock file " + path_ + ": " + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string pid = error == EWOULDBLOCK ? holder_of(fd) : "";
      ::close(fd);
      if (error == EWOULDBLOCK)
        throw BadInput(prefix + "another sweep (pid " + pid + ") is writing this output (it holds " + path_ +
                       "); run one sweep at a time per output");
      throw BadInput(prefix + "cannot lock " + path_ + ": " + std::strerror(error));
    }
    if (!still_there(fd, path_)) {
      ::close(fd);
      continue;
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
      const int error = errno;
      ::unlink(path_.c_str());
      ::close(fd);
      throw BadInput(prefix + "cannot write the lock file " + path_ + ": " + std::strerror(error));
    }
    fd_ = fd;
    return;
  }
  throw BadInput(prefix + "cannot take the lock " + path_ + ": it keeps being removed and created");
}

OutputLock::OutputLock(OutputLock&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)) {}

OutputLock& OutputLock::operator=(OutputLock&& other) noexcept {
  if (this != &other) {
    release();
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

OutputLock::~OutputLock() { release(); }

void OutputLock::release() noexcept {
  if (fd_ < 0) return;
  // Removed while still held, so that no other sweep can lock this file after we let go
  // and believe it holds the lock of the name.
  ::unlink(path_.c_str());
  ::close(fd_);
  fd_ = -1;
}

}  // namespace pb::app
