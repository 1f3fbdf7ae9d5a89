#include "app/partial_output.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
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

}  // namespace

std::size_t PartialRecord::index(std::string_view column) const {
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k] == column) return k;
  throw std::runtime_error("partial file: no column " + std::string(column));
}

std::string PartialRecord::field(std::size_t k) const { return csv_field(line, k); }

void write_from_partial(const std::string& partial, std::size_t points, std::ostream& out,
                        const std::function<void(const PartialRecord&)>& each) {
  std::ifstream in(partial, std::ios::binary);
  std::string record;
  if (!in || !read_csv_record(in, record)) throw std::runtime_error(partial + ": cannot read the partial file");
  const std::vector<std::string> columns = split_csv(record);
  std::vector<std::uint64_t> start(points, kNone);
  std::vector<std::uint32_t> length(points, 0);
  // read_csv_record takes a record and its line end: counted here, where a tellg() per line was
  // a system call each.
  for (std::uint64_t at = static_cast<std::uint64_t>(in.tellg()); read_csv_record(in, record);) {
    const std::uint64_t next = at + record.size() + 1;
    std::size_t point = 0;
    if (!point_of(record, point) || point >= points || start[point] != kNone)
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
