#include "cases/record.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <vector>

#include "cases/case.hpp"
#include "cases/input_file.hpp"
#include "cases/text.hpp"

namespace pb {

namespace {

[[noreturn]] void fail(std::string_view source, std::size_t line, const std::string& why) {
  // The file's name as given, clipped: a 100,000-character name gives a line, not a page.
  throw RecordError(clip(source, kMaxEchoedReason) + (line > 0 ? ":" + std::to_string(line) : "") + ": " + why);
}

// A value in a message: six digits, never std::to_string's hundreds for -1e308.
std::string six_digits(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
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

// The lines of a text with their numbers (from 1), the CRs before a line end dropped (LF,
// CRLF and CR CR LF endings); a CR elsewhere (old Mac line ends, which would run the whole
// file into one line) is refused.
template <class F>
void for_each_line(std::string_view text, std::string_view source, F&& f) {
  std::size_t line = 1;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view piece = text.substr(0, end);
    while (!piece.empty() && piece.back() == '\r') piece.remove_suffix(1);
    if (piece.find('\r') != std::string_view::npos)
      fail(source, line, "a CR inside the line: line ends must be LF, CRLF or CR CR LF");
    f(piece, line++);
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
}

void add_sample(Record& r, double t, double a, std::size_t line) {
  if (r.t.size() >= kMaxRecordSamples)
    fail(r.source, line, "more than " + std::to_string(kMaxRecordSamples) + " samples (the reference takes each as an event)");
  if (!std::isfinite(t) || t < 0.0) fail(r.source, line, "t: must be finite and >= 0 (got " + six_digits(t) + ")");
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
  for_each_line(text, source, [&](std::string_view piece, std::size_t line) {
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

// The fields of a line, split at blanks (a CR of a CR CR LF ending included).
std::vector<std::string_view> fields(std::string_view line) {
  std::vector<std::string_view> out;
  while (true) {
    const std::size_t begin = line.find_first_not_of(" \t\r");
    if (begin == std::string_view::npos) return out;
    line.remove_prefix(begin);
    const std::size_t end = line.find_first_of(" \t\r");
    out.push_back(line.substr(0, end));
    if (end == std::string_view::npos) return out;
    line.remove_prefix(end);
  }
}

// A line of values: every field a number (and at least one).
bool numbers_only(std::string_view line) {
  const std::vector<std::string_view> f = fields(line);
  return !f.empty() && std::all_of(f.begin(), f.end(), [](std::string_view x) { return number(x).has_value(); });
}

// An AT2 header's unit of acceleration and its factor to m/s^2 (cases/README.md, "Records").
struct Unit {
  std::string_view name;
  double si;
};
constexpr std::array<Unit, 4> kUnits = {{{"g", kStandardGravity}, {"gal", 0.01}, {"cm/s^2", 0.01}, {"m/s^2", 1.0}}};

// A unit as written ("G.", "GAL", "CM/SEC/SEC", "(M/S**2)"), lower case, in kUnits' spelling
// where it is one of them: "sec" is "s", "s/s", "s2", "s**2" are "s^2".
std::string unit_word(std::string_view word) {
  while (!word.empty() && (word.front() == '(' || word.front() == '['))
    word.remove_prefix(1);
  while (!word.empty() && std::string_view(".,;:)]").find(word.back()) != std::string_view::npos)
    word.remove_suffix(1);
  std::string w;
  for (char c : word) w += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const auto replace = [&](std::string_view from, std::string_view to) {
    for (std::size_t at = w.find(from); at != std::string::npos; at = w.find(from, at + to.size()))
      w.replace(at, from.size(), to);
  };
  replace("sec", "s");
  replace("**", "^");
  if (w.ends_with("/s/s")) w.replace(w.size() - 4, 4, "/s^2");
  if (w.ends_with("/s2")) w.replace(w.size() - 3, 3, "/s^2");
  if (w == "gals") w = "gal";
  return w;
}

const Unit* known_unit(std::string_view word) {
  for (const Unit& u : kUnits)
    if (u.name == word) return &u;
  return nullptr;
}

// Words a header puts between "UNITS" and the unit itself ("UNITS OF G", "UNITS: GAL",
// "The units are (g)", "units in cm/s2").
bool linking_word(std::string_view field) {
  const std::string word = unit_word(field);
  return word.empty() || word == "of" || word == "in" || word == "are" || word == "is" || word == "=";
}

// Whether a word reads as a unit of acceleration: one poundbench knows, or a ratio ("ft/s2").
bool unit_like(std::string_view field) {
  const std::string word = unit_word(field);
  return known_unit(word) || word.find('/') != std::string::npos;
}

// The unit a header line names, as written: after "UNITS" or "UNIT" the first word that
// reads as a unit ("UNITS OF G", "The units are (g)": OpenSees' El Centro file), else the
// first word past the linking words (of, in, are, is, "=", ":"), which the caller refuses as
// a unit it does not know; or the word after "IN" where that word is a unit ("ACCELERATION
// IN CM/S/S"), so "IN UNITS OF GAL" names gal and no word merely containing a G names g.
// "" when none.
std::string_view named_unit(std::string_view line) {
  const std::vector<std::string_view> f = fields(line);
  for (std::size_t i = 0; i < f.size(); ++i) {
    const std::string word = unit_word(f[i]);  // "(UNITS", "UNITS:" are "units"
    if (word == "units" || word == "unit") {
      const auto rest = f.begin() + static_cast<std::ptrdiff_t>(i) + 1;
      if (const auto unit = std::find_if(rest, f.end(), unit_like); unit != f.end()) return *unit;
      if (const auto other = std::find_if_not(rest, f.end(), linking_word); other != f.end()) return *other;
    } else if (word == "in" && i + 1 < f.size() && unit_like(f[i + 1])) {
      return f[i + 1];
    }
  }
  return {};
}

// The number after KEY in "NPTS= 3930, DT= .0100 SEC" (any case; '=' or ':' after the key,
// blanks around it): KEY must be a word of its own and the number runs to the next blank,
// comma or letter other than an exponent's.
std::optional<double> keyed(const std::string& line, std::string_view key, bool& has_key) {
  for (std::size_t at = line.find(key); at != std::string::npos; at = line.find(key, at + 1)) {
    if (at > 0 && std::isalpha(static_cast<unsigned char>(line[at - 1]))) continue;
    std::size_t i = at + key.size();
    while (i < line.size() && line[i] == ' ') ++i;
    if (i == line.size() || (line[i] != '=' && line[i] != ':')) continue;
    has_key = true;
    ++i;
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::size_t end = i;
    while (end < line.size() && std::string_view("0123456789.+-ED").find(line[end]) != std::string_view::npos) ++end;
    // "E" or "D" only as an exponent: "5SEC" ends the number at S, ".01 DT" never reads the D.
    while (end > i && (line[end - 1] == 'E' || line[end - 1] == 'D')) --end;
    return number(std::string_view(line).substr(i, end - i));
  }
  return std::nullopt;
}

struct Npts {
  std::optional<double> npts, dt;
};

// NPTS and DT of a header line that names NPTS ("NPTS= 3930, DT= .0100 SEC", "NPTS= 4800,
// dt= .005", or the older "3930 .0100 NPTS, DT"); nullopt for a line that does not.
std::optional<Npts> npts_line(std::string_view piece) {
  const std::string line = upper(piece);
  std::size_t word = line.find("NPTS");
  while (word != std::string::npos && word > 0 && std::isalpha(static_cast<unsigned char>(line[word - 1])))
    word = line.find("NPTS", word + 1);
  if (word == std::string::npos) return std::nullopt;
  Npts out;
  bool keyed_npts = false, keyed_dt = false;
  out.npts = keyed(line, "NPTS", keyed_npts);
  out.dt = keyed(line, "DT", keyed_dt);
  if (!keyed_npts && !keyed_dt) {  // the values first, then the names
    std::string values = line.substr(0, word);
    std::replace(values.begin(), values.end(), ',', ' ');
    const std::vector<std::string_view> f = fields(values);
    out.npts = f.size() >= 1 ? number(f[0]) : std::nullopt;
    out.dt = f.size() >= 2 ? number(f[1]) : std::nullopt;
  }
  return out;
}

constexpr const char* kNptsForm = "(\"NPTS= <n>, DT= <step> SEC\" or \"<n> <step> NPTS, DT\")";

// PEER's AT2 (record.hpp): the header is every line before the first line of numbers; one of
// its lines gives NPTS and DT, and its lines may name the unit. Then exactly NPTS values, any
// number a line, and after them only lines that do not start with a number (a trailer such as
// "*** End Data ***") or blank ones.
Record parse_at2(std::string_view text, std::string_view source) {
  Record r;
  r.source = source;
  std::optional<Npts> given;
  std::size_t given_line = 0, unit_line = 0;
  const Unit* unit = &kUnits[0];  // a header that names no unit: PEER's g
  bool header = true;
  std::size_t count = 0, expected = 0, last = 0;
  for_each_line(text, source, [&](std::string_view piece, std::size_t line) {
    // The header: every line up to the NPTS line, and after it each line that does not start
    // with a number (a units line may follow it).
    const std::vector<std::string_view> first = fields(piece);
    if (header && (given ? first.empty() || !number(first.front()) : !numbers_only(piece))) {
      if (const std::optional<Npts> n = npts_line(piece)) {
        if (given)
          fail(source, line, "a second NPTS line (the first is line " + std::to_string(given_line) + ")");
        given = n;
        given_line = line;
        if (!n->npts || *n->npts != std::floor(*n->npts) || *n->npts < 2 ||
            *n->npts > static_cast<double>(kMaxRecordSamples))
          fail(source, line, "NPTS: not a whole number of points from 2 to " + std::to_string(kMaxRecordSamples) +
                                 " " + kNptsForm);
        if (!n->dt || !std::isfinite(*n->dt) || *n->dt <= 0.0)
          fail(source, line, std::string("DT: not a positive time step ") + kNptsForm);
        expected = static_cast<std::size_t>(*n->npts);
      }
      if (const std::string_view named = named_unit(piece); !named.empty()) {
        const Unit* u = known_unit(unit_word(named));
        if (!u)
          fail(source, line, "units: '" + clip(named) + "' is not a unit of acceleration poundbench reads (g, gal, "
                             "cm/s^2, m/s^2)");
        if (unit_line > 0 && u != unit)
          fail(source, line, "units: " + std::string(u->name) + " here, " + std::string(unit->name) + " on line " +
                                 std::to_string(unit_line));
        unit = u;
        unit_line = line;
      }
      return;
    }
    if (header) {
      header = false;
      if (!given)
        fail(source, line, std::string("no NPTS/DT line in the header (the lines before the values) ") + kNptsForm);
    }
    const std::vector<std::string_view> values = fields(piece);
    if (values.empty()) return;
    if (count == expected) {
      if (number(values.front()))
        fail(source, line, "more values than NPTS = " + std::to_string(expected) + " (line " +
                               std::to_string(given_line) + ")");
      return;  // a trailer
    }
    for (const std::string_view field : values) {
      if (count == expected)
        fail(source, line, "more values than NPTS = " + std::to_string(expected) + " (line " +
                               std::to_string(given_line) + ")");
      const std::optional<double> v = number(field);
      if (!v && field == values.front())
        fail(source, line, "the values end after " + std::to_string(count) + " of NPTS = " +
                               std::to_string(expected) + " (\"" + clip(field) + "\")");
      if (!v) fail(source, line, "value " + std::to_string(count + 1) + ": not a number (\"" + clip(field) + "\")");
      add_sample(r, static_cast<double>(count) * *given->dt, *v * unit->si, line);
      ++count;
      last = line;
    }
  });
  if (!given) fail(source, 0, std::string("no NPTS/DT line and no values ") + kNptsForm);
  if (count != expected)
    fail(source, given_line, "NPTS = " + std::to_string(expected) + ", but the file holds " + std::to_string(count) +
                                 " values");
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

double record_step(const Record& r, double h_max, int k) {
  const double dt = r.interval();
  // 1e-9: DT / h_max whole up to round-off (h_max = DT / m given) keeps that m.
  const double m = std::max(static_cast<double>(k), std::ceil(dt / h_max - 1e-9));
  return dt / m;
}

double Record::mean_frequency() const { return 2.0 * std::numbers::pi / t_m; }

std::string no_mean_period_reason() {
  char band[64];
  std::snprintf(band, sizeof band, "%g and %g Hz", kMeanPeriodBand[0], kMeanPeriodBand[1]);
  return std::string("it has no mean period (no Fourier amplitude between ") + band +
         ") to take w_p from: give w_p or tp";
}

double Record::length_scale() const {
  const double w_m = mean_frequency();
  return peak / (w_m * w_m);
}

std::shared_ptr<const Record> read_record(const std::filesystem::path& file) {
  const std::string text = read_input_file<RecordError>(file);
  return std::make_shared<const Record>(parse_record(text, file.string()));
}

}  // namespace pb
