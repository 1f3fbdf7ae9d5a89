#pragma once
// Rows read back from the CSV that sweep/row.hpp writes: how a resumed sweep gets the rows
// of its partial file, and how the ranks of an MPI job send rows to rank 0.
//
// A row read back prints the same CSV line, bit for bit, and gives the same summaries
// (sweep/stats.hpp, sweep/stability.hpp). The CSV carries min_gap already divided by the
// length scale, so a row read back holds that ratio in Result::min_gap with length_scale
// 1; min_gap_ratio and penetration, the only users of the two, then give the same values.
// What the CSV does not carry stays at its default: Result::t_max, step and history, and
// the Pi terms of a body the scene does not have.

#include <istream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "sweep/row.hpp"

namespace pb {

// A CSV record that is not a row; what() names the column and the reason.
struct RowReadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The fields of one CSV record, unquoted as RFC 4180 says.
std::vector<std::string> split_csv(std::string_view record);

// Reads one record (several lines when a quoted field holds a line break) into `record`,
// without its final '\n'. Returns false at the end of the input, and also for a last
// record that the input ends in the middle of (no final '\n': a write cut short).
bool read_csv_record(std::istream& in, std::string& record);

// The row of csv_line's fields; throws RowReadError.
Row parse_row(const std::vector<std::string>& fields);

}  // namespace pb
