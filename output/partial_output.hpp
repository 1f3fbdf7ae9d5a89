#pragma once
// A one-run sweep's output (`spectrum`) built from its partial file, so that no process holds
// the sweep's rows: the partial file has each row's line, exactly the output's, in the order
// the rows finished (output/partial_rows.hpp). One pass reads where each point's line starts
// (12 bytes a point), a second copies the lines in point order. A million-point sweep held
// 1.5 KB a point in rows and lines until its end, 1.54 GB at its peak (issue 36).

#include <cstddef>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace pb::app {

// One row's line (without its line end) with the columns of its header: a field by name is read
// from the line when asked (the sweep's verdicts read 4 of its 76).
struct PartialRecord {
  PartialRecord(const std::vector<std::string>& columns_, std::string_view line_) : columns(columns_), line(line_) {}
  const std::vector<std::string>& columns;
  std::string_view line;
  // The index of a column (std::runtime_error if the header has none), and field k (fields
  // asked for in their order are read on from the last one).
  std::size_t index(std::string_view column) const;
  std::string field(std::size_t k) const;
  std::string field(std::string_view column) const { return field(index(column)); }

 private:
  mutable std::size_t last_field_ = 0, last_start_ = 0;  // the last field read, and where it starts
};

// Writes csv_header() and the line of every point 0 .. points-1 of `partial` in point order
// to `out`; `each`, when given, sees each row's line in that order. Throws
// std::runtime_error naming the file when a point has no line or two.
void write_from_partial(const std::string& partial, std::size_t points, std::ostream& out,
                        const std::function<void(const PartialRecord&)>& each = {});

}  // namespace pb::app
