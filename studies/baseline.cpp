#include "studies/baseline.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <tuple>

#include "cases/fields.hpp"
#include "rows/row_read.hpp"
#include "studies/workprecision.hpp"

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

}  // namespace

double baseline_tolerance(std::string_view solver) {
  // Another program's solver, unknown here: as the reference.
  const SolverInfo* info = find_solver(solver);
  return info ? info->baseline_tolerance : reference_solver().baseline_tolerance;
}

std::vector<Row> run_baseline(std::span<const Case> cases, const SettingsList* list, const SweepOptions& options) {
  SettingsList runs = list ? *list : SettingsList{};
  runs.reference_tol_scale = 1.0;  // the reference as users run it
  // One timing (not stored); the rows carry the monitor's measurements, as the list says.
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

bool Comparison::passed(Match m) const {
  if (failed > 0) return false;
  return m == Match::reference ? compared > 0 : unmatched == 0 && missing == 0;
}

std::vector<Comparison> compare_rows(std::span<const Row> rows, std::span<const Row> stored, Match match,
                                     double tolerance) {
  // The stored row of each (setting, case); in reference mode the setting is the reference's.
  std::map<std::string, const Row*> index;
  std::map<std::string, std::size_t> stored_per_setting;
  for (const Row& s : stored) {
    if (match == Match::reference && s.solver != reference_solver().name) continue;
    const std::string setting = match == Match::reference ? std::string() : setting_key(s);
    index.emplace(setting + '\n' + case_key(s.input), &s);
    ++stored_per_setting[setting];
  }
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
    const auto found = index.find(stored_setting + '\n' + case_key(r.input));
    if (found == index.end()) {
      ++c.unmatched;
      continue;
    }
    ++c.compared;
    ++matched_per_setting[stored_setting];
    const double d = difference(r, *found->second);
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
      c.missing = stored_per_setting[setting] - matched_per_setting[setting];
    }
  }
  return table;
}

std::string comparison_table(std::span<const Comparison> table, Match match) {
  std::ostringstream out;
  out << std::left << std::setw(22) << "family" << std::setw(40) << "solver setting" << std::right << std::setw(9)
      << "compared" << std::setw(8) << "failed" << std::setw(10) << "unmatched" << std::setw(9) << "missing"
      << std::setw(16) << "max rel |dPi1|" << std::setw(11) << "tolerance" << "  verdict\n";
  for (const Comparison& c : table) {
    std::string setting = c.solver + (c.variant.empty() ? "" : " " + c.variant);
    if (!c.settings.empty()) setting += " " + c.settings;
    if (setting.size() > 38) setting = setting.substr(0, 35) + "...";
    std::ostringstream worst;
    worst << std::setprecision(2) << std::scientific << c.max_difference;
    std::ostringstream tol;
    tol << std::setprecision(0) << std::scientific << c.tolerance;
    out << std::left << std::setw(22) << c.family << std::setw(40) << setting << std::right << std::setw(9)
        << c.compared << std::setw(8) << c.failed << std::setw(10) << c.unmatched << std::setw(9) << c.missing
        << std::setw(16) << worst.str() << std::setw(11) << tol.str() << "  "
        << (c.passed(match) ? "pass" : "FAIL") << '\n';
  }
  return out.str();
}

}  // namespace pb
