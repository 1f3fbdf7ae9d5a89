#include "studies/baseline.hpp"

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <tuple>

#include "cases/fields.hpp"
#include "cases/text.hpp"
#include "rows/row_read.hpp"
#include "studies/workprecision.hpp"
#include "solvers/registry.hpp"

namespace pb {

namespace {

constexpr std::string_view kFirstLine = " poundbench baseline";


std::string setting_key(const Row& r) { return r.solver + '\n' + r.variant + '\n' + r.settings; }

bool same_status_and_finite(const Row& a, const Row& b) {
  return a.result.status == b.result.status && std::isfinite(a.result.pi1) == std::isfinite(b.result.pi1);
}

// |Pi1 - stored| / |stored|; 0 when both are not finite, inf when the statuses differ.
double difference(const Row& row, const Row& stored) {
  if (!same_status_and_finite(row, stored)) return std::numeric_limits<double>::infinity();
  if (!std::isfinite(row.result.pi1)) return 0.0;
  if (row.result.pi1 == stored.result.pi1) return 0.0;
  return std::abs(row.result.pi1 - stored.result.pi1) / std::abs(stored.result.pi1);
}

// A case as compare_rows matches it: what must be equal (scene, pulse, directivity, the
// text and whole-number fields: a record's file, bodies, cycles), and the numbers that
// match within kCaseMatchTolerance, pi2 first (cases/fields.hpp's order).
struct CaseShape {
  std::string exact;
  std::vector<double> numbers;
  std::vector<std::string_view> names;
};

CaseShape shape_of(const Case& c) {
  CaseShape s{std::string(name(c.scene)) + ';' + std::string(name(c.pulse)) + ';' + std::string(name(c.directivity)),
              {}, {}};
  for (const CaseField& field : kCaseFields) {
    if (!written(field, c)) continue;
    if (field.yielding) s.exact += ';' + std::string(field.name);  // cases that yield alike have the same numbers
    if (field.number) {
      s.numbers.push_back(c.*field.number);
      s.names.push_back(field.name);
    } else {
      // A record by its file's name: a stored row names it relative to where the run was
      // made, a rerun by the path its case set resolved.
      const std::string text = field.text ? c.*field.text : format_number(field.get(c));
      s.exact += ';' + std::string(field.name) + '=' +
                 (field.text == &Case::record ? std::filesystem::path(text).filename().string() : text);
    }
  }
  return s;
}

double relative_gap(double a, double b) {
  if (a == b) return 0.0;
  return std::abs(a - b) / std::max(std::abs(a), std::abs(b));
}

// The largest relative gap between two cases' numbers (the same exact part: the same fields).
double distance(const CaseShape& a, const CaseShape& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.numbers.size(); ++i) d = std::max(d, relative_gap(a.numbers[i], b.numbers[i]));
  return d;
}

// "pair sine normal pi2=0.5 pi3=0.5 ...": a case as an unmatched row's line names it.
std::string case_text(const Case& c, const CaseShape& s) {
  std::string text =
      std::string(name(c.scene)) + ' ' + std::string(name(c.pulse)) + ' ' + std::string(name(c.directivity));
  for (std::size_t i = 0; i < s.numbers.size(); ++i)
    text += ' ' + std::string(s.names[i]) + '=' + format_number(s.numbers[i]);
  for (const CaseField& field : kCaseFields)
    if (written(field, c) && !field.number)
      text += ' ' + std::string(field.name) + '=' + (field.text ? c.*field.text : format_number(field.get(c)));
  return text;
}

struct StoredCase {
  const Row* row;
  CaseShape shape;
};

// The stored rows by setting and exact part, each group sorted by Pi2, so that a row's
// candidates are the few within the tolerance of its Pi2.
class StoredIndex {
 public:
  void add(const std::string& setting, const Row& row) {
    CaseShape shape = shape_of(row.input);
    groups_[setting + '\n' + shape.exact].push_back({&row, std::move(shape)});
  }
  void sort() {
    const auto by_pi2 = [](const StoredCase& a, const StoredCase& b) {
      return a.shape.numbers[0] < b.shape.numbers[0];
    };
    for (auto& [key, group] : groups_) std::stable_sort(group.begin(), group.end(), by_pi2);
  }
  // The nearest stored case within the tolerance, or null.
  const Row* match(const std::string& setting, const CaseShape& shape) const {
    const auto found = groups_.find(setting + '\n' + shape.exact);
    if (found == groups_.end()) return nullptr;
    const std::vector<StoredCase>& group = found->second;
    const double pi2 = shape.numbers[0];  // > 0 (a valid case's frequency ratio)
    const double low = pi2 * (1.0 - kCaseMatchTolerance), high = pi2 / (1.0 - kCaseMatchTolerance);
    auto it = std::lower_bound(group.begin(), group.end(), low,
                               [](const StoredCase& s, double x) { return s.shape.numbers[0] < x; });
    const Row* best = nullptr;
    double best_d = kCaseMatchTolerance;
    for (; it != group.end() && it->shape.numbers[0] <= high; ++it) {
      const double d = distance(shape, it->shape);
      if (d <= best_d) best_d = d, best = it->row;
    }
    return best;
  }
  // What the nearest stored case is, for an unmatched row: its family, point and the
  // numbers that differ beyond the tolerance (a scan of the row's group: only a few rows
  // of a comparison line are named).
  std::string nearest(const std::string& setting, const CaseShape& shape) const {
    const auto found = groups_.find(setting + '\n' + shape.exact);
    if (found == groups_.end() || found->second.empty())
      return "no stored case of " + describe_exact(shape.exact) + (setting.empty() ? "" : " with its setting");
    const StoredCase* best = nullptr;
    double best_d = 0.0;
    for (const StoredCase& s : found->second)
      if (const double d = distance(shape, s.shape); !best || d < best_d) best_d = d, best = &s;
    std::string text = "the nearest stored case is family " + best->row->input.family + " point " +
                       std::to_string(best->row->point) + ":";
    for (std::size_t i = 0; i < shape.numbers.size(); ++i) {
      const double gap = relative_gap(shape.numbers[i], best->shape.numbers[i]);
      if (gap <= kCaseMatchTolerance) continue;
      std::ostringstream apart;
      apart << std::setprecision(1) << std::scientific << gap;
      text += ' ' + std::string(shape.names[i]) + '=' + format_number(best->shape.numbers[i]) + " (" + apart.str() +
              " apart)";
    }
    return text;
  }

 private:
  // "pair sine normal" (and a record's file, a chain's bodies) from an exact part.
  static std::string describe_exact(std::string text) {
    std::replace(text.begin(), text.end(), ';', ' ');
    return text;
  }
  std::map<std::string, std::vector<StoredCase>> groups_;
};

}  // namespace

double baseline_tolerance(std::string_view solver) {
  // Another program's solver, unknown here: as the reference.
  const SolverInfo* info = find_solver(solver);
  return info ? info->baseline_tolerance : reference_solver().baseline_tolerance;
}

std::vector<Row> run_baseline(std::span<const Case> cases, const SettingsList* list, const SweepOptions& options) {
  SettingsList runs = list ? *list : SettingsList{};
  runs.reference_tol_scale = 1.0;  // the reference as users run it
  // One solve a point, with the monitor on where the list says so (its timing is not stored).
  WorkPrecision wp = run_work_precision(cases, runs, options, {1, true});
  if (!wp.complete) return {};
  std::vector<Row> rows = std::move(wp.reference);
  rows.insert(rows.end(), std::make_move_iterator(wp.points.begin()), std::make_move_iterator(wp.points.end()));
  for (Row& r : rows) clear_timing(r);
  return rows;
}

std::vector<std::string> header_lines(const BaselineHeader& h) {
  std::vector<std::string> out = {std::string(kFirstLine), " cases: " + h.cases,
                                  " settings: " + (h.settings.empty() ? std::string("none") : h.settings)};
  for (const std::string& note : h.notes) out.push_back(" " + note);
  return out;
}

BaselineHeader parse_header(std::span<const std::string> comments, std::string_view source) {
  if (comments.empty() || comments.front() != kFirstLine)
    throw RowReadError(std::string(source) + ":1: header: not a poundbench baseline (no '#" +
                         std::string(kFirstLine) + "' line)");
  BaselineHeader h;
  bool has_cases = false, has_settings = false;
  for (std::size_t i = 1; i < comments.size(); ++i) {
    const std::string& line = comments[i];
    if (line.starts_with(" cases: ")) {
      h.cases = line.substr(8);
      has_cases = true;
    } else if (line.starts_with(" settings: ")) {
      h.settings = line.substr(11) == "none" ? "" : line.substr(11);
      has_settings = true;
    } else {
      h.notes.push_back(line.substr(line.starts_with(' ') ? 1 : 0));
    }
  }
  if (!has_cases || h.cases.empty()) throw RowReadError(std::string(source) + ": cases: missing header line");
  if (!has_settings) throw RowReadError(std::string(source) + ": settings: missing header line");
  return h;
}

bool Comparison::passed(Match m, bool allow_unmatched) const {
  if (failed > 0 || compared == 0) return false;
  if (unmatched > 0 && !allow_unmatched) return false;
  return m == Match::reference || missing == 0;
}

std::vector<Comparison> compare_rows(std::span<const Row> rows, std::span<const Row> stored, Match match,
                                     double tolerance) {
  // The stored rows of each setting; in reference mode the setting is the reference's.
  StoredIndex index;
  std::map<std::string, std::size_t> stored_per_setting;
  for (const Row& s : stored) {
    if (match == Match::reference && s.solver != reference_solver().name) continue;
    const std::string setting = match == Match::reference ? std::string() : setting_key(s);
    index.add(setting, s);
    ++stored_per_setting[setting];
  }
  index.sort();
  std::vector<Comparison> table;
  std::map<std::tuple<std::string, std::string>, std::size_t> line_of;  // (family, setting) -> line
  std::map<std::string, std::size_t> matched_per_setting;
  for (const Row& r : rows) {
    const std::string setting = setting_key(r);
    auto [it, fresh] = line_of.try_emplace({r.input.family, setting}, table.size());
    if (fresh) {
      Comparison c;
      c.family = r.input.family;
      c.solver = r.solver;
      c.variant = r.variant;
      c.settings = r.settings;
      c.tolerance = std::isnan(tolerance) ? baseline_tolerance(r.solver) : tolerance;
      table.push_back(c);
    }
    Comparison& c = table[it->second];
    const std::string stored_setting = match == Match::reference ? std::string() : setting;
    const CaseShape shape = shape_of(r.input);
    const Row* found = index.match(stored_setting, shape);
    if (!found) {
      if (++c.unmatched <= kNamedUnmatched)
        c.unmatched_rows.push_back({r.point, case_text(r.input, shape), index.nearest(stored_setting, shape)});
      continue;
    }
    ++c.compared;
    ++matched_per_setting[stored_setting];
    const double d = difference(r, *found);
    if (!(d <= c.tolerance)) ++c.failed;
    if (c.compared == 1 || d > c.max_difference) {
      c.max_difference = d;
      c.worst_point = r.point;
    }
  }
  if (match == Match::same_setting) {
    // Stored rows that no row matched: counted on the setting's first line.
    std::map<std::string, bool> counted;
    for (Comparison& c : table) {
      const std::string setting = c.solver + '\n' + c.variant + '\n' + c.settings;
      if (counted[setting]) continue;
      counted[setting] = true;
      const std::size_t matched = matched_per_setting[setting], total = stored_per_setting[setting];
      c.missing = total > matched ? total - matched : 0;
    }
  }
  return table;
}

std::string setting_text(const Comparison& c) {
  std::string setting = c.solver + (c.variant.empty() ? "" : " " + c.variant);
  if (!c.settings.empty()) setting += " " + c.settings;
  return setting.empty() ? "-" : setting;  // rows that name no solver (compare's minimal columns)
}

std::string comparison_table(std::span<const Comparison> table, Match match, bool allow_unmatched) {
  std::size_t family_width = 8, setting_width = 16;
  for (const Comparison& c : table) {
    family_width = std::max(family_width, c.family.size() + 2);
    setting_width = std::max(setting_width, setting_text(c).size() + 2);
  }
  const int fw = static_cast<int>(family_width), sw = static_cast<int>(setting_width);
  std::ostringstream out;
  out << std::left << std::setw(fw) << "family" << std::setw(sw) << "solver setting" << std::right << std::setw(9)
      << "compared" << std::setw(8) << "failed" << std::setw(10) << "unmatched" << std::setw(9) << "missing"
      << std::setw(16) << "max rel |dPi1|" << std::setw(11) << "tolerance" << "  verdict\n";
  const auto family = [](const Comparison& c) { return c.family.empty() ? std::string("-") : c.family; };
  for (const Comparison& c : table) {
    std::ostringstream worst;
    worst << std::setprecision(2) << std::scientific << c.max_difference;
    std::ostringstream tol;
    tol << std::setprecision(0) << std::scientific << c.tolerance;
    out << std::left << std::setw(fw) << family(c) << std::setw(sw) << setting_text(c) << std::right << std::setw(9)
        << c.compared << std::setw(8) << c.failed << std::setw(10) << c.unmatched << std::setw(9) << c.missing
        << std::setw(16) << (c.compared ? worst.str() : "-") << std::setw(11) << tol.str() << "  "
        << (c.passed(match, allow_unmatched) ? "pass" : "FAIL") << '\n';
  }
  for (const Comparison& c : table) {
    for (const Unmatched& u : c.unmatched_rows)
      out << "unmatched: " << family(c) << ' ' << setting_text(c) << ": point " << u.point << " (" << u.row_case
          << "): no stored case within " << kCaseMatchTolerance << " (relative); " << u.nearest << '\n';
    if (c.unmatched > c.unmatched_rows.size())
      out << "unmatched: " << family(c) << ' ' << setting_text(c) << ": and "
          << c.unmatched - c.unmatched_rows.size() << " more rows\n";
  }
  return out.str();
}

}  // namespace pb
