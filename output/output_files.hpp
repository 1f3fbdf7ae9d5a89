#pragma once
// Output files that never leave a half-written result under their final name: each is
// written next to its target as "<target>.tmp" and renamed into place when complete.
// Targets are checked before anything is created, so a bad flag leaves no file behind.

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <span>
#include <string_view>
#include <vector>

#include "cases/case.hpp"
#include "cases/case_list.hpp"

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

// A file a command reads or writes, and what names it ("--out", "CASESET", "record").
struct NamedFile {
  std::string name;
  std::filesystem::path path;
};

// Throws BadInput ("<input>: <file>: would be overwritten by --out ...", "--points: <file>:
// is also --out ...") when a file a command writes is one of its inputs (a case set, a
// settings list, a record), or when two of them are one: the outputs, each output's
// temporary, and a sweep's partial file and its lock (output/resumable_sweep.hpp; "" when the
// command has none). Two paths are one file when fs::equivalent says so, or, where one does
// not exist yet, when their absolute paths with symlinks resolved are equal.
void check_outputs_apart(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs,
                         std::string_view partial = {}, std::string_view lock = {});

// The record files of `cases`, each once, as inputs named "record".
std::vector<NamedFile> record_files(const CaseList& cases);

// Writes `file` through "<file>.tmp" and a rename; throws std::runtime_error on failure
// naming the reason (the temporary is removed then). A device or a pipe (/dev/null) is
// written in place.
void write_atomically(const std::filesystem::path& file, const std::function<void(std::ostream&)>& write);

// Writes to stdout; throws std::runtime_error ("stdout: write failed: <reason>").
void write_to_stdout(const std::function<void(std::ostream&)>& write);

// An append-only text file that receives its lines in batches, so that a file written a
// line at a time from a sweep costs one write per batch instead of one per line (the paper
// set's 23 820 rows were 23 820 flushed writes, each under the sweep's lock). A line added
// reaches the operating system once the batch is due: when its oldest line has waited
// `max_delay`, or the batch holds kMaxBatchBytes; add_line() and write_due() write a due
// batch, and the owner calls write_due() at least every so often so that a line never
// waits much longer than max_delay for the next one. flush() and close() write whatever
// is kept, and so does the destructor (its failure then unreported), so that lines kept
// when an exception unwinds are not lost. The caller serialises the calls.
//
// A failed write is kept: that call and every later one throw std::runtime_error
// "<file>: write failed: <reason>", and the lines not written stay unwritten.
class BatchedFile {
 public:
  enum class Mode { truncate, append };
  using Duration = std::chrono::steady_clock::duration;
  static constexpr std::size_t kMaxBatchBytes = 1 << 20;

  BatchedFile(const std::filesystem::path& file, Mode mode, Duration max_delay);  // throws on failure
  ~BatchedFile();
  BatchedFile(const BatchedFile&) = delete;
  BatchedFile& operator=(const BatchedFile&) = delete;

  void add_line(std::string_view line);  // the line without its end; writes the batch when due
  void write_due();                      // writes the batch if it is due
  void flush();                          // writes the batch now
  void close();                          // flush(), then close the file
  const std::filesystem::path& path() const { return path_; }

 private:
  void write_batch();

  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  Duration max_delay_;
  std::string batch_;                               // lines kept, each with its end
  std::chrono::steady_clock::time_point oldest_{};  // when the batch's first line was added
  std::string error_;                               // the failure of an earlier write
};

}  // namespace pb::app
