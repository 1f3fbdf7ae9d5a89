#include "sweep/row_read.hpp"

#include <charconv>
#include <cstddef>
#include <limits>
#include <optional>

namespace pb {

namespace {

constexpr std::size_t kFields = 37;  // csv_header()'s columns

std::optional<Status> parse_status(std::string_view text) {
  for (Status s : {Status::ok, Status::diverged, Status::nan, Status::step_cap, Status::timeout, Status::failed})
    if (name(s) == text) return s;
  return std::nullopt;
}

// Reads csv_line's fields in the order it writes them, naming the column of a bad one.
class FieldReader {
 public:
  explicit FieldReader(const std::vector<std::string>& fields) : fields_(fields) {
    if (fields.size() != kFields)
      throw RowReadError(std::to_string(fields.size()) + " fields, a row has " + std::to_string(kFields));
  }

  const std::string& text(std::string_view column) {
    column_ = column;
    return fields_[next_++];
  }
  // An empty field is `missing` (NaN unless the column says otherwise).
  double number(std::string_view column, double missing = std::numeric_limits<double>::quiet_NaN()) {
    const std::string& field = text(column);
    if (field.empty()) return missing;
    double x = 0.0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), x);
    if (error != std::errc{} || end != field.data() + field.size()) fail("not a number");
    return x;
  }
  template <typename Int>
  Int count(std::string_view column, Int missing = 0) {
    const std::string& field = text(column);
    if (field.empty()) return missing;
    Int n = 0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), n);
    if (error != std::errc{} || end != field.data() + field.size()) fail("not an integer");
    return n;
  }
  template <typename T>
  T named(std::string_view column, std::optional<T> (*parse)(std::string_view)) {
    const std::optional<T> value = parse(text(column));
    if (!value) fail("unknown name");
    return *value;
  }
  [[noreturn]] void fail(std::string_view reason) const {
    throw RowReadError(std::string(column_) + ": " + std::string(reason) + " (\"" + fields_[next_ - 1] + "\")");
  }

 private:
  const std::vector<std::string>& fields_;
  std::size_t next_ = 0;
  std::string_view column_;
};

}  // namespace

std::vector<std::string> split_csv(std::string_view record) {
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

Row parse_row(const std::vector<std::string>& fields) {
  FieldReader f(fields);
  Row row;
  Case& c = row.input;
  Result& r = row.result;
  c.family = f.text("family");
  row.point = f.count<std::size_t>("point");
  c.scene = f.named("scene", &parse_scene);
  c.pulse = f.named("pulse", &parse_pulse);
  c.directivity = f.named("directivity", &parse_directivity);
  c.pi2 = f.number("pi2");
  c.pi3 = f.number("pi3");
  c.eps = f.number("eps");
  // Empty where the scene has no such body: the Case keeps its default there.
  for (auto [pi, column] : {std::pair{&c.pi5, "pi5"}, {&c.pi6, "pi6"}, {&c.pi7, "pi7"}, {&c.pi8, "pi8"}})
    *pi = f.number(column, *pi);
  c.xi = f.number("xi");
  c.n_free = f.number("n_free");
  c.a_p = f.number("a_p");
  c.w_p = f.number("w_p");
  row.solver = f.text("solver");
  row.variant = f.text("variant");
  row.settings = f.text("settings");
  r.status = f.named("status", &parse_status);
  r.pi1 = f.number("pi1");
  row.pi1_no_contact = f.number("pi1_no_contact");
  r.impacts = f.count<long>("impacts");
  r.contact_phases = f.count<long>("contact_phases");
  r.steps = f.count<long>("steps");
  r.min_gap = f.number("min_gap", std::numeric_limits<double>::infinity());  // empty: no contact closed
  row.length_scale = 1.0;
  row.seconds = f.number("seconds");
  row.cpu_seconds = f.number("cpu_seconds");
  r.message = f.text("message");
  c.bodies = f.count<int>("bodies", c.bodies);
  c.kick = f.number("kick", c.kick);
  row.wh = f.number("wh");
  r.energy_excess = f.number("energy_excess");
  f.number("penetration");  // derived from min_gap and pi3
  r.isolated_impacts = f.count<long>("isolated_impacts");
  r.restitution_low = f.number("restitution_low");
  r.restitution_high = f.number("restitution_high");
  return row;
}

}  // namespace pb
