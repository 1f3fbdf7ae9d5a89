#pragma once
// Result rows read back from the CSV that write_csv (sweep/row.hpp) writes: what a stored
// baseline, or another program's rows in the same columns, holds.
//
// Columns are found by name, so their order does not matter and extra columns are ignored.
// The case columns and family, point, solver, variant, settings, status and pi1 are
// required; every other column that Row holds is read when present (an empty field is NaN,
// or 0 for a count). The column computed from others (penetration) is not read back. Lines that start with '#' before the header are comments (a baseline's
// provenance); a quoted field may hold commas, quotes and line breaks (RFC 4180).

#include <istream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "sweep/row.hpp"

namespace pb {

// what() is one line: "<source>:<line>: <column>: <reason>".
struct RowFormatError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct RowFile {
  std::vector<std::string> comments;  // the '#' lines before the header, without the '#'
  std::vector<Row> rows;
};

RowFile read_csv(std::istream& in, std::string_view source);
RowFile read_csv_file(const std::string& path);

// One CSV record split into its fields (quotes removed, doubled quotes undone).
std::vector<std::string> split_csv_record(std::string_view record);

}  // namespace pb
