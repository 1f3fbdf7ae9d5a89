#include "sweep/row_reader.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

namespace pb {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Records of the text, each with the line it starts on; a quoted field may span lines.
struct Record {
  std::string text;
  long line;
};

std::vector<Record> records(std::string_view text) {
  std::vector<Record> out;
  std::string current;
  bool quoted = false;
  long line = 1, start = 1;
  for (char ch : text) {
    if (ch == '"') quoted = !quoted;
    if (ch == '\n' && !quoted) {
      if (!current.empty() && current.back() == '\r') current.pop_back();
      out.push_back({std::move(current), start});
      current.clear();
      start = line + 1;
    } else {
      current += ch;
    }
    if (ch == '\n') ++line;
  }
  if (!current.empty()) out.push_back({std::move(current), start});
  return out;
}

class Fields {
 public:
  Fields(const std::map<std::string, std::size_t>& columns, std::vector<std::string> values,
         std::string_view source, long line)
      : columns_(columns), values_(std::move(values)), source_(source), line_(line) {}

  [[noreturn]] void fail(std::string_view column, std::string_view why) const {
    std::ostringstream out;
    out << source_ << ':' << line_ << ": " << column << ": " << why;
    throw RowFormatError(out.str());
  }

  // The field of a column; nullopt when the file has no such column.
  std::optional<std::string_view> get(const std::string& column) const {
    const auto it = columns_.find(column);
    if (it == columns_.end()) return std::nullopt;
    return std::string_view(values_[it->second]);
  }

  std::string text(const std::string& column) const { return std::string(get(column).value_or("")); }

  // A number; an empty field or a missing optional column is `missing`.
  double number(const std::string& column, double missing = kNaN) const {
    const std::string_view v = get(column).value_or("");
    if (v.empty()) return missing;
    double x = 0.0;
    const auto [end, error] = std::from_chars(v.data(), v.data() + v.size(), x);
    if (error != std::errc{} || end != v.data() + v.size()) fail(column, "not a number: '" + std::string(v) + "'");
    return x;
  }

  long count(const std::string& column) const {
    const double x = number(column, 0.0);
    if (x != std::floor(x)) fail(column, "not a whole number");
    return static_cast<long>(x);
  }

 private:
  const std::map<std::string, std::size_t>& columns_;
  std::vector<std::string> values_;
  std::string_view source_;
  long line_;
};

std::optional<Status> parse_status(std::string_view s) {
  for (Status v : {Status::ok, Status::diverged, Status::nan, Status::step_cap, Status::timeout, Status::failed})
    if (name(v) == s) return v;
  return std::nullopt;
}

Row parse_row(const Fields& f) {
  Row row;
  Case& c = row.input;
  c.family = f.text("family");
  row.point = static_cast<std::size_t>(f.count("point"));
  const auto scene = parse_scene(f.text("scene"));
  if (!scene) f.fail("scene", "unknown scene '" + f.text("scene") + "'");
  c.scene = *scene;
  const auto pulse = parse_pulse(f.text("pulse"));
  if (!pulse) f.fail("pulse", "unknown pulse '" + f.text("pulse") + "'");
  c.pulse = *pulse;
  const auto directivity = parse_directivity(f.text("directivity"));
  if (!directivity) f.fail("directivity", "unknown directivity '" + f.text("directivity") + "'");
  c.directivity = *directivity;
  const Case defaults;
  c.pi2 = f.number("pi2");
  c.pi3 = f.number("pi3");
  c.eps = f.number("eps");
  c.pi5 = f.number("pi5", defaults.pi5);  // empty where the scene lacks the body
  c.pi6 = f.number("pi6", defaults.pi6);
  c.pi7 = f.number("pi7", defaults.pi7);
  c.pi8 = f.number("pi8", defaults.pi8);
  c.xi = f.number("xi");
  c.n_free = f.number("n_free");
  c.a_p = f.number("a_p");
  c.w_p = f.number("w_p");
  c.bodies = static_cast<int>(f.count("bodies"));
  c.kick = f.number("kick", 0.0);
  row.solver = f.text("solver");
  if (row.solver.empty()) f.fail("solver", "empty");
  row.variant = f.text("variant");
  row.settings = f.text("settings");
  const auto status = parse_status(f.text("status"));
  if (!status) f.fail("status", "unknown status '" + f.text("status") + "'");
  Result& r = row.result;
  r.status = *status;
  r.message = f.text("message");
  r.pi1 = f.number("pi1");
  r.impacts = f.count("impacts");
  r.contact_phases = f.count("contact_phases");
  r.steps = f.count("steps");
  row.length_scale = c.a_p / (c.w_p * c.w_p);
  r.min_gap = f.number("min_gap", std::numeric_limits<double>::infinity()) * row.length_scale;
  r.energy_excess = f.number("energy_excess");
  r.isolated_impacts = f.count("isolated_impacts");
  r.restitution_low = f.number("restitution_low");
  r.restitution_high = f.number("restitution_high");
  row.pi1_no_contact = f.number("pi1_no_contact");
  row.wh = f.number("wh");
  row.penetration_steps = f.number("penetration_steps");
  row.seconds = f.number("seconds", 0.0);
  row.cpu_seconds = f.number("cpu_seconds", 0.0);
  return row;
}

}  // namespace

std::vector<std::string> split_csv_record(std::string_view record) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < record.size(); ++i) {
    const char ch = record[i];
    if (quoted && ch == '"' && i + 1 < record.size() && record[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (ch == '"') {
      quoted = !quoted;
    } else if (ch == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += ch;
    }
  }
  return fields;
}

RowFile read_csv(std::istream& in, std::string_view source) {
  std::ostringstream text;
  text << in.rdbuf();
  RowFile file;
  const std::vector<Record> lines = records(text.str());
  std::size_t k = 0;
  for (; k < lines.size() && lines[k].text.starts_with('#'); ++k) file.comments.push_back(lines[k].text.substr(1));
  if (k == lines.size()) throw RowFormatError(std::string(source) + ": no header line");
  std::map<std::string, std::size_t> columns;
  const std::vector<std::string> header = split_csv_record(lines[k].text);
  for (std::size_t i = 0; i < header.size(); ++i) columns.emplace(header[i], i);
  for (const char* required : {"family", "point", "scene", "pulse", "directivity", "pi2", "pi3", "eps", "xi",
                               "n_free", "a_p", "w_p", "solver", "variant", "settings", "status", "pi1"})
    if (!columns.contains(required)) {
      std::ostringstream out;
      out << source << ':' << lines[k].line << ": " << required << ": missing column";
      throw RowFormatError(out.str());
    }
  for (++k; k < lines.size(); ++k) {
    if (lines[k].text.empty()) continue;
    std::vector<std::string> values = split_csv_record(lines[k].text);
    if (values.size() != header.size()) {
      std::ostringstream out;
      out << source << ':' << lines[k].line << ": row: " << values.size() << " fields, the header has "
          << header.size();
      throw RowFormatError(out.str());
    }
    file.rows.push_back(parse_row(Fields(columns, std::move(values), source, lines[k].line)));
  }
  return file;
}

RowFile read_csv_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw RowFormatError(path + ": cannot read: no such file or not readable");
  return read_csv(in, path);
}

}  // namespace pb
