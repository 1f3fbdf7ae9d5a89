#pragma once
// Output files that never leave a half-written result under their final name: each is
// written next to its target as "<target>.tmp" and renamed into place when complete.
// Targets are checked before anything is created, so a bad flag leaves no file behind.

#include <cstdio>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>

namespace pb::app {

// Throws BadInput ("<flag>: <file>: <reason>") unless a file can be created at `file`:
// it is not a directory, its directory exists and is writable, and the temporary next to
// it can be created (it is, and removed again).
void check_output_target(const std::filesystem::path& file, std::string_view flag);

// check_output_target, and also refuses what is not a regular file or a new name (a
// device such as /dev/full, a pipe): a sweep writes its output through a temporary file
// and keeps its partial file next to it, neither of which a device's directory is for.
// Such outputs go to stdout, the sweeps' default.
void check_sweep_output(const std::filesystem::path& file, std::string_view flag);

// Writes `file` through "<file>.tmp" and a rename; throws std::runtime_error on failure
// naming the reason (the temporary is removed then). A device or a pipe (/dev/null) is
// written in place.
void write_atomically(const std::filesystem::path& file, const std::function<void(std::ostream&)>& write);

// Writes to stdout; throws std::runtime_error ("stdout: write failed: <reason>").
void write_to_stdout(const std::function<void(std::ostream&)>& write);

// An append-only text file whose every line reaches the operating system as soon as it
// is written, so that it survives an interrupt or a crash of the program.
class FlushedFile {
 public:
  enum class Mode { truncate, append };
  explicit FlushedFile(const std::filesystem::path& file, Mode mode = Mode::truncate);  // throws on failure
  ~FlushedFile();
  FlushedFile(const FlushedFile&) = delete;
  FlushedFile& operator=(const FlushedFile&) = delete;

  void write_line(std::string_view line);  // throws std::runtime_error on failure
  void close();
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
};

}  // namespace pb::app
