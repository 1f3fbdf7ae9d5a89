#include "rows/row_read.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include "cases/fields.hpp"
#include "cases/physical.hpp"
#include "rows/result_fields.hpp"
#include "cases/input_file.hpp"

namespace pb {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Reads a record's fields by column name, naming the column of a bad one.
class FieldReader {
 public:
  FieldReader(const Columns& columns, const std::vector<std::string>& fields) : columns_(columns), fields_(fields) {
    if (fields.size() != columns.size())
      throw RowReadError(std::to_string(fields.size()) + " fields, the header has " + std::to_string(columns.size()));
  }

  // The field, or "" when the header has no such column.
  const std::string& text(const std::string& column) {
    column_ = column;
    const std::string* field = columns_.find(fields_, column);
    return field ? *field : empty_;
  }
  // An empty field is `missing` (NaN unless the column says otherwise).
  double number(const std::string& column, double missing = kNaN) { return parsed(column, missing, "not a number"); }
  template <typename Int>
  Int count(const std::string& column, Int missing = 0) {
    return parsed(column, missing, "not an integer");
  }
  // Numbers separated by ';' (LineBuilder::numbers); an empty field is none, an empty item NaN.
  std::vector<double> numbers(const std::string& column) {
    const std::string& field = text(column);
    std::vector<double> out;
    if (field.empty()) return out;
    for (std::size_t at = 0;;) {
      const std::size_t end = std::min(field.find(';', at), field.size());
      double x = kNaN;
      if (end > at) {
        const auto [stop, error] = std::from_chars(field.data() + at, field.data() + end, x);
        if (error != std::errc{} || stop != field.data() + end) fail(field, "not a list of numbers separated by ';'");
      }
      out.push_back(x);
      if (end == field.size()) return out;
      at = end + 1;
    }
  }
  template <typename T>
  T named(const std::string& column, std::optional<T> (*parse)(std::string_view)) {
    const std::string& field = text(column);
    const std::optional<T> value = parse(field);
    if (!value) fail(field, "unknown name");
    return *value;
  }

 private:
  // The whole field read by std::from_chars as a T, `missing` where it is empty.
  template <typename T>
  T parsed(const std::string& column, T missing, std::string_view not_a_t) {
    const std::string& field = text(column);
    if (field.empty()) return missing;
    T x{};
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), x);
    if (error != std::errc{} || end != field.data() + field.size()) fail(field, not_a_t);
    return x;
  }

  [[noreturn]] void fail(const std::string& field, std::string_view reason) const {
    throw RowReadError(column_ + ": " + std::string(reason) + " (\"" + field + "\")");
  }

  const Columns& columns_;
  const std::vector<std::string>& fields_;
  std::string column_;
  const std::string empty_;
};

// Every record of a text with the line it starts on; a quoted field may span lines.
struct CsvRecord {
  std::string text;
  std::size_t line;
};

std::vector<CsvRecord> records(std::istream& in) {
  std::vector<CsvRecord> out;
  std::size_t line = 1;
  std::string record, piece;
  bool quoted = false;
  std::size_t start = 1;
  while (std::getline(in, piece)) {
    if (!piece.empty() && piece.back() == '\r') piece.pop_back();
    if (record.empty() && !quoted) start = line;
    for (char ch : piece)
      if (ch == '"') quoted = !quoted;
    record += piece;
    ++line;
    if (quoted) {
      record += '\n';
      continue;
    }
    out.push_back({std::move(record), start});
    record.clear();
  }
  if (!record.empty()) out.push_back({std::move(record), start});
  return out;
}

}  // namespace

Columns::Columns(const std::vector<std::string>& header) : size_(header.size()) {
  for (std::size_t i = 0; i < header.size(); ++i) index_.emplace(header[i], i);
  const auto require = [&](std::string_view column) {
    if (!index_.contains(column)) throw RowReadError(std::string(column) + ": missing column");
  };
  for (const char* column : {"family", "point", "scene", "pulse", "directivity"}) require(column);
  for (const CaseField& field : kCaseFields)
    if (field.use == FieldUse::every && !field.yielding) require(field.name);
  for (const char* column : {"solver", "variant", "settings", "status", "pi1"}) require(column);
}

const std::string* Columns::find(const std::vector<std::string>& fields, const std::string& column) const {
  const auto it = index_.find(column);
  return it == index_.end() ? nullptr : &fields[it->second];
}

namespace {

// Reads the field that starts at `at` into `out`, unquoted; returns where the next one starts, or
// npos after the record's last. The text between two quotes or separators is appended as one
// run: a character at a time, splitting was 7 % of a `spectrum` of the paper set (its output
// read back from the partial file, issue 36).
std::size_t read_csv_field(std::string_view record, std::size_t at, std::string& out) {
  out.clear();
  bool quoted = false;
  std::size_t i = at;
  while (i < record.size()) {
    std::size_t j = i;
    while (j < record.size() && record[j] != '"' && (quoted || record[j] != ',')) ++j;
    out.append(record.substr(i, j - i));
    if (j == record.size()) break;
    i = j + 1;
    if (record[j] == ',') return i;
    if (quoted && i < record.size() && record[i] == '"') {
      out += '"';  // a doubled quote inside quotes
      ++i;
    } else {
      quoted = !quoted;
    }
  }
  return std::string_view::npos;
}

}  // namespace

std::vector<std::string> split_csv(std::string_view record) {
  std::vector<std::string> fields;
  std::size_t at = 0;
  do {
    at = read_csv_field(record, at, fields.emplace_back());
  } while (at != std::string_view::npos);
  return fields;
}

std::string csv_field(std::string_view record, std::size_t k) {
  std::string field;
  std::size_t at = 0;
  for (std::size_t i = 0; i <= k; ++i) {
    if (at == std::string_view::npos) return {};
    at = read_csv_field(record, at, field);
  }
  return field;
}

bool read_csv_record(std::istream& in, std::string& record) {
  record.clear();
  std::string line;
  bool quoted = false;  // inside a quoted field at the end of what was read
  while (std::getline(in, line)) {
    if (in.eof()) return false;  // no '\n' after it: cut short
    for (char ch : line)
      if (ch == '"') quoted = !quoted;  // a doubled quote toggles twice
    record += line;
    if (!quoted) return true;
    record += '\n';
  }
  return false;
}

Row parse_row(const Columns& columns, const std::vector<std::string>& fields) {
  FieldReader f(columns, fields);
  Row row;
  Case& c = row.input;
  Result& r = row.result;
  c.family = f.text("family");
  row.point = f.count<std::size_t>("point");
  c.scene = f.named("scene", &parse_scene);
  c.pulse = f.named("pulse", &parse_pulse);
  c.directivity = f.named("directivity", &parse_directivity);
  // Every number of the case by its column. Those of every scene must be there; those of
  // some scenes' bodies, and those of yielding, are empty elsewhere (or missing, in older
  // files) and keep the Case's default there.
  for (const CaseField& field : kCaseFields) {
    const std::string column(field.name);
    if (field.use == FieldUse::every && !field.yielding)
      c.*field.number = f.number(column);
    else if (field.text)
      c.*field.text = f.text(column);
    else if (field.number)
      c.*field.number = f.number(column, c.*field.number);
    else
      c.*field.integer = f.count<int>(column, c.*field.integer);
  }
  // The physical units (cases/physical.hpp), before the results: contact_force_max is read per unit of m0.
  for (const PhysicalField& field : kPhysicalFields) c.physical.*field.member = f.number(std::string(field.name));
  // Every result field by its column (rows/result_fields.hpp): a column missing from an older
  // file reads as an empty field; a field made from others (mu, penetration) is made again.
  for (const ResultField& field : kResultFields) {
    if (field.place == Place::none) continue;
    const std::string column(field.name);
    switch (field.type) {
      case ResultType::number: field.read(row, f.number(column, field.missing)); break;
      case ResultType::count:
        field.read(row, static_cast<double>(f.count<long long>(column, static_cast<long long>(field.missing))));
        break;
      case ResultType::text:
      case ResultType::object: field.store_text(row, f.text(column)); break;
      case ResultType::status: r.status = f.named(column, &parse_status); break;
      case ResultType::verdict: r.resolved = f.named(column, &parse_resolved); break;  // a file from before it: not judged
      case ResultType::list: field.store_list(row, f.numbers(column)); break;
    }
  }
  if (const std::string bad = row_problem(row); !bad.empty()) throw RowReadError(bad);
  return row;
}

Row parse_row(const std::vector<std::string>& fields) {
  static const Columns standard(split_csv(csv_header()));
  return parse_row(standard, fields);
}

RowFile read_csv(std::istream& in, std::string_view source) {
  const std::vector<CsvRecord> lines = records(in);
  const auto fail = [&](std::size_t line, const std::string& why) {
    std::ostringstream out;
    out << source << ':' << line << ": " << why;
    return RowReadError(out.str());
  };
  RowFile file;
  std::size_t k = 0;
  for (; k < lines.size() && lines[k].text.starts_with('#'); ++k) file.comments.push_back(lines[k].text.substr(1));
  if (k == lines.size()) throw fail(lines.empty() ? 1 : lines.back().line, "header: no header line");
  std::optional<Columns> columns;
  try {
    columns.emplace(split_csv(lines[k].text));
  } catch (const RowReadError& e) {
    throw fail(lines[k].line, e.what());
  }
  for (++k; k < lines.size(); ++k) {
    if (lines[k].text.empty()) continue;
    try {
      file.rows.push_back(parse_row(*columns, split_csv(lines[k].text)));
    } catch (const RowReadError& e) {
      throw fail(lines[k].line, e.what());
    }
  }
  return file;
}

RowFile read_csv_file(const std::string& path) {
  std::istringstream in(read_input_file<RowReadError>(path));
  return read_csv(in, path);
}

}  // namespace pb
