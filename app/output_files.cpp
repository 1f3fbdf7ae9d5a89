#include "app/output_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "app/errors.hpp"

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

}  // namespace

void check_output_target(const fs::path& file, std::string_view flag) {
  const std::string prefix = std::string(flag) + ": " + file.string() + ": ";
  std::error_code ec;
  if (file.empty()) throw BadInput(std::string(flag) + ": empty file name");
  if (fs::is_directory(file, ec)) throw BadInput(prefix + "is a directory");
  if (is_special(file)) {
    if (::access(file.c_str(), W_OK) != 0) throw BadInput(prefix + "is not writable");
    return;
  }
  fs::path dir = file.parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir, ec)) throw BadInput(prefix + "directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0) throw BadInput(prefix + "directory " + dir.string() + " is not writable");
  if (fs::exists(file, ec) && ::access(file.c_str(), W_OK) != 0) throw BadInput(prefix + "is not writable");
  probe_temporary(file, prefix);
}

void write_atomically(const fs::path& file, const std::function<void(std::ostream&)>& write) {
  if (is_special(file)) {
    std::ofstream out(file);
    if (!out) throw std::runtime_error(file.string() + ": cannot open: " + std::strerror(errno));
    write(out);
    out.flush();
    if (!out) throw std::runtime_error(file.string() + ": write failed");
    return;
  }
  const fs::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) throw std::runtime_error(tmp.string() + ": cannot create: " + std::strerror(errno));
    write(out);
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw std::runtime_error(tmp.string() + ": write failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error(file.string() + ": cannot rename " + tmp.string() + " into place: " + ec.message());
  }
}

FlushedFile::FlushedFile(const fs::path& file, Mode mode)
    : path_(file), file_(std::fopen(file.c_str(), mode == Mode::append ? "a" : "w")) {
  if (!file_) throw std::runtime_error(file.string() + ": cannot create: " + std::strerror(errno));
}

FlushedFile::~FlushedFile() {
  if (file_) std::fclose(file_);
}

void FlushedFile::write_line(std::string_view line) {
  if (!file_) throw std::runtime_error(path_.string() + ": write after close");
  const bool ok = std::fwrite(line.data(), 1, line.size(), file_) == line.size() && std::fputc('\n', file_) != EOF &&
                  std::fflush(file_) == 0;
  if (!ok) throw std::runtime_error(path_.string() + ": write failed: " + std::strerror(errno));
}

void FlushedFile::close() {
  if (file_ && std::fclose(file_) != 0) {
    file_ = nullptr;
    throw std::runtime_error(path_.string() + ": close failed: " + std::strerror(errno));
  }
  file_ = nullptr;
}

}  // namespace pb::app
