#include "cases/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "cases/case.hpp"
#include "cases/text.hpp"

namespace pb {

namespace {

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "is a directory";
  if (S_ISFIFO(mode)) return "not a regular file (a FIFO: it would wait for a writer)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "not a regular file (a device)";
  if (S_ISSOCK(mode)) return "not a regular file (a socket)";
  return "not a regular file";
}

// Opens `file` to read and says why it is not a regular file (nullopt when it is); fd is -1
// when it could not be opened.
std::optional<std::string> open_regular(const std::filesystem::path& file, int& fd, struct stat& st) {
  fd = -1;
  if (file.empty()) return "empty file name";
  // O_NONBLOCK: a FIFO with no writer opens at once (and is then refused) instead of waiting.
  fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return std::string(std::strerror(errno));
  if (::fstat(fd, &st) != 0) return std::string(std::strerror(errno));
  if (!S_ISREG(st.st_mode)) return kind_of(st.st_mode);
  return std::nullopt;
}

}  // namespace

std::optional<std::string> read_regular_file(const std::filesystem::path& file, std::string& text) {
  text.clear();
  int fd = -1;
  struct stat st {};
  std::optional<std::string> why = open_regular(file, fd, st);
  if (fd < 0) return why;
  if (!why && static_cast<unsigned long long>(st.st_size) > kMaxInputBytes)
    why = "larger than " + std::to_string(kMaxInputBytes >> 20) + " MB (" + std::to_string(st.st_size) + " bytes)";
  if (!why) {
    text.reserve(static_cast<std::size_t>(st.st_size));
    char buffer[1 << 16];
    while (true) {
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        why = std::string("read error: ") + std::strerror(errno);
        break;
      }
      if (n == 0) break;
      text.append(buffer, static_cast<std::size_t>(n));
      // A file that grows while it is read is bounded all the same.
      if (text.size() > kMaxInputBytes) {
        why = "larger than " + std::to_string(kMaxInputBytes >> 20) + " MB";
        break;
      }
    }
  }
  ::close(fd);
  if (why) text.clear();
  return why;
}

std::optional<std::string> regular_file_problem(const std::filesystem::path& file) {
  int fd = -1;
  struct stat st {};
  const std::optional<std::string> why = open_regular(file, fd, st);
  if (fd >= 0) ::close(fd);
  return why;
}

std::string cannot_read(const std::filesystem::path& file, const std::string& why) {
  return clip(file.string(), kMaxEchoedReason) + ": cannot read: " + why;
}

}  // namespace pb
