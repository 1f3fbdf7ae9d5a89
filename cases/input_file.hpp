#pragma once
// Reading an input file whole (a case set, a settings list, a record, rows to compare, a
// partial file): what every reader of poundbench shares, so that none of them blocks on a
// FIFO nobody writes to, reads /dev/zero until memory runs out, or takes a directory.
//
// Only a regular file is read (after symlinks): it is opened without blocking (a FIFO
// opens at once) and refused by what fstat says it is, so no file can change between the
// check and the read. At most kMaxInputBytes are read: the largest shipped input, the paper
// set's stored baseline (tests/baselines/paper-reference.csv), is 5.6 MB, and a settings
// list, case set or record 40 times that is a mistake, not a study.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace pb {

inline constexpr std::size_t kMaxInputBytes = std::size_t{256} << 20;

// The file's text, or why it cannot be read ("is a directory", "not a regular file (a
// FIFO)", "larger than 256 MB", strerror's reason); `text` is left empty then.
std::optional<std::string> read_regular_file(const std::filesystem::path& file, std::string& text);

// Why `file` is not a regular file that can be opened, as read_regular_file says it, or
// nullopt; no size limit. For a reader that streams a file too large to hold: a sweep's
// partial file, 450 MB at a million points.
std::optional<std::string> regular_file_problem(const std::filesystem::path& file);

// The file's text; throws Error("<file>: cannot read: <why>") (the name clipped).
template <class Error>
std::string read_input_file(const std::filesystem::path& file);

// The message of a file that cannot be read: "<file>: cannot read: <why>", the name clipped.
std::string cannot_read(const std::filesystem::path& file, const std::string& why);

template <class Error>
std::string read_input_file(const std::filesystem::path& file) {
  std::string text;
  if (const std::optional<std::string> why = read_regular_file(file, text)) throw Error(cannot_read(file, *why));
  return text;
}

}  // namespace pb
