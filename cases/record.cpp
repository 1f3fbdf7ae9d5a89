#include "cases/record.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>

#include "cases/case.hpp"
#include "cases/toml_input.hpp"

namespace pb {

namespace {

[[noreturn]] void fail(std::string_view source, std::size_t line, const std::string& why) {
  throw RecordError(std::string(source) + (line > 0 ? ":" + std::to_string(line) : "") + ": " + why);
}

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// A number as a record writes it: a decimal (Fortran's ".2320975E-03" and "1.5D-03"
// included, and a leading '+'), the whole field and nothing else.
std::optional<double> number(std::string_view field) {
  field = trim(field);
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty()) return std::nullopt;
  std::string text(field);
  for (char& c : text)
    if (c == 'D' || c == 'd') c = 'E';
  double x = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return x;
}

// The lines of a text with their numbers (from 1), a CR before a line end dropped.
template <class F>
void for_each_line(std::string_view text, F&& f) {
  std::size_t line = 1;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view piece = text.substr(0, end);
    if (!piece.empty() && piece.back() == '\r') piece.remove_suffix(1);
    f(piece, line++);
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
}

void add_sample(Record& r, double t, double a, std::size_t line) {
  if (r.t.size() >= kMaxRecordSamples)
    fail(r.source, line, "more than " + std::to_string(kMaxRecordSamples) + " samples (the reference takes each as an event)");
  if (!std::isfinite(t) || t < 0.0) fail(r.source, line, "t: must be finite and >= 0 (got " + std::to_string(t) + ")");
  if (!r.t.empty() && !(t > r.t.back()))
    fail(r.source, line, std::string("t: ") + (t == r.t.back() ? "repeats" : "goes back from") +
                             " the time before it (times must rise strictly)");
  if (!std::isfinite(a)) fail(r.source, line, "a_g: must be finite");
  r.t.push_back(t);
  r.a.push_back(a);
  r.peak = std::max(r.peak, std::abs(a));
}

void finish(const Record& r, std::size_t last_line) {
  if (r.t.empty()) fail(r.source, 1, "no samples (an empty record)");
  if (r.t.size() < 2) fail(r.source, last_line, "one sample: a record needs at least two");
  if (!(r.peak > 0.0)) fail(r.source, 0, "every acceleration is zero (no peak to take a_p from)");
}

Record parse_csv(std::string_view text, std::string_view source) {
  Record r;
  r.source = source;
  bool first = true;
  std::size_t last = 0;
  for_each_line(text, [&](std::string_view piece, std::size_t line) {
    const std::string_view s = trim(piece);
    if (s.empty() || s.front() == '#') return;
    last = line;
    const std::size_t comma = s.find(',');
    const std::string_view left = s.substr(0, comma);
    const std::string_view right = comma == std::string_view::npos ? std::string_view{} : s.substr(comma + 1);
    const std::optional<double> t = number(left);
    const std::optional<double> a = number(right);
    const bool header = first && !t && !a;
    first = false;
    if (header) return;
    if (comma == std::string_view::npos) fail(source, line, "expected two columns \"t, a_g\", got one");
    if (right.find(',') != std::string_view::npos) fail(source, line, "expected two columns \"t, a_g\", got more");
    if (!t) fail(source, line, "t: not a number (\"" + clip(trim(left)) + "\")");
    if (!a) fail(source, line, "a_g: not a number (\"" + clip(trim(right)) + "\")");
    add_sample(r, *t, *a, line);
  });
  finish(r, last);
  return r;
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// The number after "KEY=" in the line (NGA-West2's "NPTS=  3930, DT=   .0100 SEC").
std::optional<double> keyed(const std::string& line, std::string_view key) {
  const std::size_t at = line.find(std::string(key) + "=");
  if (at == std::string::npos) return std::nullopt;
  std::size_t begin = at + key.size() + 1;
  while (begin < line.size() && line[begin] == ' ') ++begin;
  std::size_t end = begin;
  while (end < line.size() && line[end] != ',' && line[end] != ' ') ++end;
  return number(std::string_view(line).substr(begin, end - begin));
}

Record parse_at2(std::string_view text, std::string_view source) {
  Record r;
  r.source = source;
  std::optional<double> npts, dt;
  std::size_t count = 0, expected = 0, last = 0;
  for_each_line(text, [&](std::string_view piece, std::size_t line) {
    if (line <= 4) {
      const std::string head = upper(piece);
      if (line == 3 && head.find("UNITS OF") != std::string::npos && head.find("UNITS OF G") == std::string::npos)
        fail(source, line, "units: an AT2 record's values are in g (\"UNITS OF G\"), this line names other units");
      if (line == 4) {
        npts = keyed(head, "NPTS");
        dt = keyed(head, "DT");
        if (!npts && !dt) {  // the older "3930   .0100   NPTS, DT"
          std::size_t split = head.find_first_of(" \t", head.find_first_not_of(" \t"));
          const std::string_view h(head);
          npts = number(h.substr(0, split));
          if (split != std::string::npos) {
            const std::string_view rest = trim(h.substr(split));
            dt = number(rest.substr(0, rest.find_first_of(" \t,")));
          }
        }
        if (!npts || *npts != std::floor(*npts) || *npts < 0 || *npts > 1e9)
          fail(source, line, "NPTS: not a whole number of points (expected \"NPTS= <n>, DT= <step> SEC\")");
        if (!dt || !std::isfinite(*dt) || *dt <= 0.0)
          fail(source, line, "DT: not a positive time step (expected \"NPTS= <n>, DT= <step> SEC\")");
        expected = static_cast<std::size_t>(*npts);
      }
      return;
    }
    std::string_view rest = piece;
    while (true) {
      const std::size_t begin = rest.find_first_not_of(" \t\r");
      if (begin == std::string_view::npos) break;
      rest.remove_prefix(begin);
      const std::size_t end = rest.find_first_of(" \t\r");
      const std::string_view field = rest.substr(0, end);
      const std::optional<double> v = number(field);
      if (!v) fail(source, line, "value " + std::to_string(count + 1) + ": not a number (\"" + clip(field) + "\")");
      if (count == expected)
        fail(source, line, "more values than NPTS = " + std::to_string(expected) + " (line 4)");
      add_sample(r, static_cast<double>(count) * *dt, *v * kStandardGravity, line);
      ++count;
      last = line;
      if (end == std::string_view::npos) break;
      rest.remove_prefix(end);
    }
  });
  if (!npts) fail(source, 0, "no NPTS/DT line (an AT2 record has four header lines, the fourth \"NPTS= <n>, DT= <step> SEC\")");
  if (count != expected)
    fail(source, 4, "NPTS = " + std::to_string(expected) + ", but the file holds " + std::to_string(count) + " values");
  finish(r, last);
  return r;
}

bool is_at2(std::string_view source) {
  return source.size() >= 4 && upper(source.substr(source.size() - 4)) == ".AT2";
}

}  // namespace

Record record_from_samples(std::vector<double> t, std::vector<double> a, std::string_view source) {
  Record r;
  r.source = source;
  if (t.size() != a.size())
    fail(source, 0, std::to_string(t.size()) + " times but " + std::to_string(a.size()) + " accelerations");
  r.t.reserve(t.size());
  r.a.reserve(a.size());
  for (std::size_t i = 0; i < t.size(); ++i) add_sample(r, t[i], a[i], i + 1);
  finish(r, t.size());
  r.t_m = mean_period(r.t, r.a);
  return r;
}

Record parse_record(std::string_view text, std::string_view source) {
  Record r = is_at2(source) ? parse_at2(text, source) : parse_csv(text, source);
  r.t_m = mean_period(r.t, r.a);
  return r;
}

double Record::length_scale() const {
  const double w_m = 2.0 * std::numbers::pi / t_m;
  return peak / (w_m * w_m);
}

std::shared_ptr<const Record> read_record(const std::filesystem::path& file) {
  const std::string text = read_input_file<RecordError>(file);
  return std::make_shared<const Record>(parse_record(text, file.string()));
}

}  // namespace pb
