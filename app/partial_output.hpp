#pragma once
// A one-run sweep's output (`spectrum`) built from its partial file, so that no process holds
// the sweep's rows: the partial file has each row's line, exactly the output's, in the order
// the rows finished (sweep/partial_rows.hpp). One pass reads where each point's line starts
// (12 bytes a point), a second copies the lines in point order. A million-point sweep held
// 1.5 KB a point in rows and lines until its end, 1.54 GB at its peak (issue 36).

#include <cstddef>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace pb::app {

// The fields of one row's line (split_csv) with the columns of its header, by name.
struct PartialRecord {
  const std::vector<std::string>& columns;
  const std::vector<std::string>& fields;
  const std::string& field(std::string_view column) const;
};

// Writes csv_header() and the line of every point 0 .. points-1 of `partial` in point order
// to `out`; `each`, when given, sees each row's fields in that order. Throws
// std::runtime_error naming the file when a point has no line or two.
void write_from_partial(const std::string& partial, std::size_t points, std::ostream& out,
                        const std::function<void(const PartialRecord&)>& each = {});

}  // namespace pb::app
