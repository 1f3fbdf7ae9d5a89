#pragma once
// Rows read back from the CSV that rows/row.hpp writes: the rows of a resumed sweep's
// partial file, the rows the ranks of an MPI job send to rank 0, a stored baseline
// (studies/baseline.hpp), and another program's rows in the same columns.
//
// A row read back prints the same CSV line, bit for bit, and gives the same summaries
// (studies/stats.hpp, studies/stress.hpp). The CSV carries min_gap already divided by the
// length scale, so a row read back holds that ratio in Result::min_gap with length_scale
// 1; min_gap_ratio and penetration, the only users of the two, then give the same values.
// What the CSV does not carry stays at its default: Result::t_max, step, gap_rate_max and
// history, and the Pi terms of a body the scene does not have.

#include <istream>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rows/row.hpp"

namespace pb {

// A CSV record that is not a row; what() names the column and the reason (and, from
// read_csv, the file and line first: "<source>:<line>: <column>: <reason>").
struct RowReadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The fields of one CSV record, unquoted as RFC 4180 says.
std::vector<std::string> split_csv(std::string_view record);
// Field k of one CSV record (split_csv(record)[k]), read without splitting the others out;
// empty past the record's last field.
std::string csv_field(std::string_view record, std::size_t k);

// Reads one record (several lines when a quoted field holds a line break) into `record`,
// without its final '\n'. Returns false at the end of the input, and also for a last
// record that the input ends in the middle of (no final '\n': a write cut short).
bool read_csv_record(std::istream& in, std::string& record);

// Where each column stands in a header record. The case columns and family, point,
// solver, variant, settings, status and pi1 are required (RowReadError otherwise); any
// other column Row holds is read when present, and unknown columns are ignored.
class Columns {
 public:
  explicit Columns(const std::vector<std::string>& header);
  // The field of `column` in a record, or nullptr when the header lacks it.
  const std::string* find(const std::vector<std::string>& fields, const std::string& column) const;
  std::size_t size() const { return size_; }

 private:
  std::map<std::string, std::size_t, std::less<>> index_;
  std::size_t size_ = 0;
};

// The row of a record under `columns`; throws RowReadError, also for a row that
// row_problem (rows/row.hpp) refuses: rows read back pass the checks of rows written.
Row parse_row(const Columns& columns, const std::vector<std::string>& fields);
// The row of csv_line's fields (the columns of csv_header, in its order).
Row parse_row(const std::vector<std::string>& fields);

// A CSV file of rows, its header found by name: the '#' lines before the header are
// comments (a baseline's provenance), returned without the '#'. A last line without its
// '\n' is read as the others (a file another program wrote).
struct RowFile {
  std::vector<std::string> comments;
  std::vector<Row> rows;
};
RowFile read_csv(std::istream& in, std::string_view source);
RowFile read_csv_file(const std::string& path);  // RowReadError when it cannot be read

}  // namespace pb
