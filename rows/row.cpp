#include "rows/row.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <utility>

#include "cases/fields.hpp"
#include "cases/text.hpp"
#include "cases/physical.hpp"
#include "rows/line_builder.hpp"
#include "rows/result_fields.hpp"

namespace pb {

void clear_timing(Row& row) {
  row.seconds = row.cpu_seconds = row.cpu_seconds_low = row.cpu_seconds_high = std::numeric_limits<double>::quiet_NaN();
  row.repetitions = 1;
}

double min_gap_ratio(const Row& row) { return row.result.min_gap / row.length_scale; }

// Through min_gap_ratio, the value the CSV carries, so that a row read back from its CSV
// line (rows/row_read.hpp) gives the same bits.
double penetration(const Row& row) { return std::max(0.0, -min_gap_ratio(row)); }

double ductility(const Row& row) {
  const double pi_y = pi_y_ref(row.input);
  return std::isfinite(pi_y) ? row.result.pi1 / pi_y : std::numeric_limits<double>::quiet_NaN();
}

double penetration_steps(const Result& r) {
  const double travel = r.step * r.gap_rate_max;
  if (std::isnan(travel)) return std::numeric_limits<double>::quiet_NaN();
  const double depth = std::max(0.0, -r.min_gap);
  return depth > 0.0 ? depth / travel : 0.0;
}

namespace {

std::string shown(double x) {
  return std::isnan(x) ? "nan" : std::isinf(x) ? (x > 0 ? "inf" : "-inf") : format_number(x);
}

}  // namespace

std::string row_problem(const Row& row) {
  const Result& r = row.result;
  if (r.status == Status::ok && !(std::isfinite(r.pi1) && r.pi1 >= 0.0))
    return "pi1: must be a finite number >= 0 when status is ok (it is " + shown(r.pi1) + ")";
  for (const auto& [count, column] : {std::pair{r.impacts, "impacts"}, {r.contact_phases, "contact_phases"},
                                      {r.steps, "steps"}, {r.isolated_impacts, "isolated_impacts"}})
    if (count < 0) return std::string(column) + ": must be >= 0 (it is " + std::to_string(count) + ")";
  for (const auto& [t, column] : {std::pair{row.seconds, "seconds"}, {row.cpu_seconds, "cpu_seconds"},
                                  {row.cpu_seconds_low, "cpu_seconds_low"}, {row.cpu_seconds_high, "cpu_seconds_high"}})
    if (!std::isnan(t) && !(std::isfinite(t) && t >= 0.0))
      return std::string(column) + ": must be a finite number >= 0, or empty (it is " + shown(t) + ")";
  if (row.repetitions < 1) return "repetitions: must be >= 1 (it is " + std::to_string(row.repetitions) + ")";
  return {};
}

std::string_view resolved_text(const std::optional<bool>& resolved) {
  return resolved ? (*resolved ? "true" : "false") : "";
}

std::optional<std::optional<bool>> parse_resolved(std::string_view text) {
  std::optional<std::optional<bool>> out;
  if (text.empty())
    out.emplace();
  else if (text == "true" || text == "false")
    out.emplace(text == "true");
  return out;
}

std::string case_key(const Case& c) {
  std::string key(name(c.scene));
  key += ';';
  key += name(c.pulse);
  key += ';';
  key += name(c.directivity);
  for (const CaseField& field : kCaseFields)
    if (written(field, c)) key += ';' + (field.text ? c.*field.text : format_number(field.get(c)));
  return key;
}

std::string csv_field(std::string_view text) {
  std::string field;
  append_csv_field(field, text);
  return field;
}

namespace {

// The columns before the case's numbers: which case, where it sits in the sweep.
constexpr std::array kLeadColumns = {"family", "point", "scene", "pulse", "directivity"};

// Where a field's column is: after the directivity (those of every scene's bodies), after
// the message (the chain's, where they were added), after the tail (the pulses'), after the
// verdict (yielding's) or last of all (a record's scaling, added after the separations).
enum class Group { body, chain, pulse, yielding, late };
Group group_of(const CaseField& f) {
  if (f.late) return Group::late;
  if (f.yielding) return Group::yielding;
  return f.use == FieldUse::chain ? Group::chain : pulse_use(f.use) ? Group::pulse : Group::body;
}

// The names of the case fields of one group: the header of case_numbers' columns.
void case_names(LineBuilder& line, Group group) {
  for (const CaseField& f : kCaseFields)
    if (group_of(f) == group) line.text(f.name);
}

// A case's fields of one group: empty where the scene and pulse do not use them.
void case_numbers(LineBuilder& line, const Case& c, Group group) {
  for (const CaseField& f : kCaseFields) {
    if (group_of(f) != group) continue;
    if (!written(f, c))
      line.text("");
    else if (f.text)
      line.text(c.*f.text);
    else if (f.integer)
      line.count(c.*f.integer);
    else
      line.number(c.*f.number);
  }
}

// A result's field (rows/result_fields.hpp) as its column shows it.
void result_cell(LineBuilder& line, const ResultField& f, const Row& row) {
  switch (f.type) {
    case ResultType::number: line.number(f.number(row)); return;
    case ResultType::count: line.count(f.whole ? row.result.*f.whole : static_cast<long long>(f.number(row))); return;
    case ResultType::text:
    case ResultType::object: line.text(f.text(row)); return;
    case ResultType::status: line.text(name(row.result.status)); return;
    case ResultType::verdict: line.text(resolved_text(row.result.resolved)); return;
    case ResultType::list: line.numbers(f.list(row)); return;
  }
}

}  // namespace

double h_over_dt(const Row& row) {
  return row.input.samples ? row.result.step / row.input.samples->interval() : std::numeric_limits<double>::quiet_NaN();
}

std::string csv_header() {
  LineBuilder line;
  for (const char* column : kLeadColumns) line.text(column);
  const auto results = [&](Place place) {
    for (const ResultField& f : kResultFields)
      if (f.place == place) line.text(f.name);
  };
  case_names(line, Group::body);
  results(Place::middle);
  case_names(line, Group::chain);
  results(Place::tail);
  case_names(line, Group::pulse);
  results(Place::verdict);
  case_names(line, Group::yielding);
  results(Place::yielding);
  for (const PhysicalField& f : kPhysicalFields) line.text(f.name);
  for (Place place : {Place::physical, Place::own_time, Place::record_step, Place::estimate, Place::separation})
    results(place);
  case_names(line, Group::late);
  return line.take();
}

std::string csv_line(const Row& row) {
  const Case& c = row.input;
  LineBuilder line;
  line.text(c.family);
  line.count(static_cast<long long>(row.point));
  line.text(name(c.scene));
  line.text(name(c.pulse));
  line.text(name(c.directivity));
  const auto results = [&](Place place) {
    for (const ResultField& f : kResultFields)
      if (f.place == place) result_cell(line, f, row);
  };
  case_numbers(line, c, Group::body);
  results(Place::middle);
  case_numbers(line, c, Group::chain);
  results(Place::tail);
  case_numbers(line, c, Group::pulse);
  results(Place::verdict);
  case_numbers(line, c, Group::yielding);
  results(Place::yielding);
  for (const PhysicalField& f : kPhysicalFields) line.number(c.physical.*f.member);
  for (Place place : {Place::physical, Place::own_time, Place::record_step, Place::estimate, Place::separation})
    results(place);
  case_numbers(line, c, Group::late);
  return line.take();
}

void write_csv(std::ostream& out, std::span<const Row> rows) {
  out << csv_header() << '\n';
  for (const Row& row : rows) out << csv_line(row) << '\n';
}

}  // namespace pb
