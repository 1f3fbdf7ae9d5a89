#include "output/partial_output.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "rows/row.hpp"
#include "rows/row_read.hpp"

namespace pb::app {

namespace {

constexpr std::uint64_t kNone = std::numeric_limits<std::uint64_t>::max();

// The point of a line (its second field, after the family, which may be quoted), without
// splitting the whole line: the first pass reads only this.
bool point_of(std::string_view line, std::size_t& point) {
  bool quoted = false;
  std::size_t commas = 0, start = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '"') quoted = !quoted;
    if (line[i] != ',' || quoted) continue;
    if (++commas == 1) {
      start = i + 1;
    } else {
      const auto [end, ec] = std::from_chars(line.data() + start, line.data() + i, point);
      return ec == std::errc() && end == line.data() + i;
    }
  }
  return false;
}

// Whether [from, to) holds an odd number of quotes (found by memchr: a few a line).
bool odd_quotes(const char* from, const char* to) {
  bool odd = false;
  while (const void* q = std::memchr(from, '"', static_cast<std::size_t>(to - from))) {
    odd = !odd;
    from = static_cast<const char*>(q) + 1;
  }
  return odd;
}

// The records of a partial file after its header, as read_csv_record reads them (a record ends
// at the first line end with an even count of quotes before it in the record: a doubled quote
// inside quotes counts twice), from its stream in chunks: read_csv_record's getline and a loop
// over every character were 2,900 instructions a line, a quarter of the output pass.
class RecordScanner {
 public:
  explicit RecordScanner(std::istream& in) : in_(in) {}
  // The next record, without its line end, valid until the next call; false at the end of the
  // file (a last record with no line end after it is cut short: no record).
  bool next(std::string_view& record) {
    bool quoted = false;
    std::size_t scanned = start_;
    for (;;) {
      const std::size_t end = buffer_.find('\n', scanned);
      const std::size_t upto = end == std::string::npos ? buffer_.size() : end;
      quoted = quoted != odd_quotes(buffer_.data() + scanned, buffer_.data() + upto);
      if (end == std::string::npos) {
        buffer_.erase(0, start_);  // the records read: dropped only as more comes in
        scanned = buffer_.size();
        start_ = 0;
        if (!more()) return false;
        continue;
      }
      scanned = end + 1;
      if (quoted) continue;  // a line end inside quotes: the record goes on
      record = std::string_view(buffer_).substr(start_, end - start_);
      start_ = end + 1;
      return true;
    }
  }

 private:
  bool more() {
    constexpr std::size_t kChunk = std::size_t{1} << 16;
    const std::size_t had = buffer_.size();
    buffer_.resize(had + kChunk);
    in_.read(buffer_.data() + had, static_cast<std::streamsize>(kChunk));
    buffer_.resize(had + static_cast<std::size_t>(in_.gcount()));
    return buffer_.size() > had;
  }

  std::istream& in_;
  std::string buffer_;     // from the first record not read yet, or before
  std::size_t start_ = 0;  // where that record starts
};

// Where field k of a CSV record starts, from field `from` starting at `at`: past k - from
// commas outside quotes, a quoted stretch skipped to its closing quote (a doubled quote inside
// quotes closes and opens it again, as read_csv_field reads it). npos where the record has
// fewer fields.
std::size_t field_start(std::string_view line, std::size_t from, std::size_t at, std::size_t k) {
  for (std::size_t i = at; from < k; ++i) {
    if (i >= line.size()) return std::string_view::npos;
    if (line[i] == '"') {
      i = line.find('"', i + 1);  // memchr over a quoted field (the settings' JSON)
      if (i == std::string_view::npos) return i;
    } else if (line[i] == ',') {
      ++from;
      at = i + 1;
    }
  }
  return at;
}

}  // namespace

std::size_t PartialRecord::index(std::string_view column) const {
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k] == column) return k;
  throw std::runtime_error("partial file: no column " + std::string(column));
}

std::string PartialRecord::field(std::size_t k) const {
  // From the last field read when k is past it (the verdicts read 4 fields of 78 in order):
  // read from the line's start each time, the fields were half of the output pass.
  const bool onward = k >= last_field_ && last_start_ != std::string_view::npos;
  const std::size_t at = field_start(line, onward ? last_field_ : 0, onward ? last_start_ : 0, k);
  last_field_ = k;
  last_start_ = at;
  return at == std::string_view::npos ? std::string() : csv_field(line.substr(at), 0);
}

void write_from_partial(const std::string& partial, std::size_t points, std::ostream& out,
                        const std::function<void(const PartialRecord&)>& each) {
  std::ifstream in(partial, std::ios::binary);
  std::string record;
  if (!in || !read_csv_record(in, record)) throw std::runtime_error(partial + ": cannot read the partial file");
  const std::vector<std::string> columns = split_csv(record);
  std::vector<std::uint64_t> start(points, kNone);
  std::vector<std::uint32_t> length(points, 0);
  // Each record and its line end counted from the header's end, where a tellg() per line was a
  // system call each.
  RecordScanner records(in);
  std::string_view read;
  for (std::uint64_t at = static_cast<std::uint64_t>(in.tellg()); records.next(read);) {
    const std::uint64_t next = at + read.size() + 1;
    std::size_t point = 0;
    if (!point_of(read, point) || point >= points || start[point] != kNone)
      throw std::runtime_error(partial + ": a line that is not one of the sweep's points, or a point's second line");
    start[point] = at;
    length[point] = static_cast<std::uint32_t>(next - at);
    at = next;
  }
  in.clear();
  out << csv_header() << '\n';
  // The lines are read through a window of the file: the rows finished nearly in point order, so
  // the next point's line is nearly always in it. A seek and a read per point were 47 642 and
  // 25 142 system calls on the paper set.
  constexpr std::uint64_t kWindow = std::uint64_t{1} << 20;
  std::string window;
  std::uint64_t window_at = 0;
  for (std::size_t p = 0; p < points; ++p) {
    if (start[p] == kNone) throw std::runtime_error(partial + ": point " + std::to_string(p) + " has no line");
    if (start[p] < window_at || start[p] + length[p] > window_at + window.size()) {
      window_at = start[p];
      window.resize(std::max<std::uint64_t>(kWindow, length[p]));
      in.clear();
      in.seekg(static_cast<std::streamoff>(window_at));
      in.read(window.data(), static_cast<std::streamsize>(window.size()));
      window.resize(static_cast<std::size_t>(in.gcount()));
      if (window.size() < length[p]) throw std::runtime_error(partial + ": cannot read the partial file");
    }
    const std::string_view line = std::string_view(window).substr(start[p] - window_at, length[p]);
    out << line;
    if (each) each(PartialRecord{columns, line.substr(0, line.size() - 1)});  // without the line end
  }
}

}  // namespace pb::app
