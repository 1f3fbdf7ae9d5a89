#include "rows/partial_line.hpp"

#include <charconv>
#include <vector>

#include "rows/row_read.hpp"

namespace pb {

namespace {

// The run column taken off the front of a record's fields.
std::size_t take_run(std::vector<std::string>& fields) {
  std::size_t run = 0;
  const std::string& text = fields.front();
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), run);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size())
    throw RowReadError("run: not an integer (\"" + text + "\")");
  fields.erase(fields.begin());
  return run;
}

}  // namespace

std::string partial_header(bool with_run) { return (with_run ? "run," : "") + csv_header(); }

std::string partial_line(const Row& row, bool with_run) {
  return (with_run ? std::to_string(row.run) + "," : "") + csv_line(row);
}

Row parse_partial_line(std::string_view record, bool with_run) {
  std::vector<std::string> fields = split_csv(record);
  const std::size_t run = with_run ? take_run(fields) : 0;
  Row row = parse_row(fields);
  row.run = run;
  return row;
}

}  // namespace pb
