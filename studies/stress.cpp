#include "studies/stress.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <sstream>

#include "cases/text.hpp"
#include "studies/stats.hpp"

namespace pb {

namespace {

bool finished(const Row& row) { return row.result.status == Status::ok && std::isfinite(row.result.pi1); }

// NaN-aware maximum: NaN (not measured) never wins, and stays only if nothing was measured.
void keep_max(double& worst, double x) {
  if (std::isnan(x)) return;
  if (std::isnan(worst) || x > worst) worst = x;
}

Verdict within(double worst, double tolerance) {
  if (std::isnan(worst)) return Verdict::none;
  return worst <= tolerance ? Verdict::pass : Verdict::fail;
}

// One summary per family over a run's rows (one row per case, in point order).
void summarize_run(std::span<const Row> rows, std::span<const TruthPoint> truth,
                   const std::vector<std::string>& families, std::vector<StressRow>& table) {
  for (const std::string& family : families) {
    std::vector<const Row*> mine;
    std::vector<TruthPoint> theirs;
    for (const Row& r : rows) {
      if (r.input.family != family) continue;
      mine.push_back(&r);
      theirs.push_back(truth[r.point]);
    }
    table.push_back(summarize_stress(mine, theirs));
  }
}

}  // namespace

std::string_view name(Verdict v) {
  switch (v) {
    case Verdict::pass: return "pass";
    case Verdict::fail: return "fail";
    case Verdict::none: return "";
  }
  return "";
}

std::string StressRow::failed_checks() const {
  std::string out;
  for (const auto& [v, check] : {std::pair{finite, "finite"}, {energy, "energy"}, {gap, "gap"},
                                 {restitution, "restitution"}, {accuracy, "accuracy"}})
    if (v == Verdict::fail) out += (out.empty() ? "" : ", ") + std::string(check);
  return out;
}

bool StressRow::passed() const { return failed_checks().empty(); }

double pi1_error(const Row& row, double reference) {
  if (!finished(row) || !std::isfinite(reference)) return std::numeric_limits<double>::quiet_NaN();
  return std::abs(row.result.pi1 - reference) / std::abs(reference);
}

double restitution_error(const Row& row) {
  const Result& r = row.result;
  if (r.isolated_impacts <= 0) return std::numeric_limits<double>::quiet_NaN();
  double worst = std::numeric_limits<double>::quiet_NaN();
  keep_max(worst, std::abs(r.restitution_low - row.input.eps));
  keep_max(worst, std::abs(r.restitution_high - row.input.eps));
  return worst;
}

StressRow summarize_stress(std::span<const Row* const> rows, std::span<const TruthPoint> truth) {
  StressRow s;
  if (!rows.empty()) {
    s.family = rows.front()->input.family;
    s.solver = rows.front()->solver;
    s.variant = rows.front()->variant;
    s.settings = rows.front()->settings;
  }
  std::vector<double> errors;
  bool any_finished = false, stepped = false;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& row = *rows[i];
    // A point whose step is beyond the step bound (pb::step_problem: longer than the pulse)
    // was never run: it is left out of the cell, not counted as a run that failed.
    if (beyond_step_bound(row.result)) continue;
    ++s.runs;
    if (!finished(row)) continue;
    ++s.ok;
    any_finished = true;
    keep_max(s.energy_excess_max, row.result.energy_excess);
    keep_max(s.penetration_max, penetration(row));
    keep_max(s.penetration_steps_max, row.penetration_steps);
    stepped = stepped || !std::isnan(row.wh);
    s.isolated_impacts += row.result.isolated_impacts;
    keep_max(s.restitution_error_max, restitution_error(row));
    const double e = pi1_error(row, truth[i].pi1);
    if (std::isnan(e)) continue;  // not compared
    errors.push_back(e);
    s.impacts += row.result.impacts;
    s.truth_impacts += truth[i].impacts;
    if (truth[i].impacts > 0 && row.result.impacts == 0) ++s.missed_impact_points;
  }
  if (!errors.empty()) {
    s.pi1_err_median = percentile(errors, 50.0);
    s.pi1_err_p95 = percentile(errors, 95.0);
    s.pi1_err_max = *std::max_element(errors.begin(), errors.end());
    s.accuracy = s.pi1_err_p95 <= kAccuracyTolerance && s.missed_impact_points == 0 ? Verdict::pass : Verdict::fail;
  }
  s.cpu = cpu_cost(rows);
  if (s.runs > 0) s.finite = s.ok == s.runs ? Verdict::pass : Verdict::fail;
  if (any_finished) {
    s.energy = within(s.energy_excess_max, kEnergyTolerance);
    s.gap = stepped ? within(s.penetration_steps_max, kPenetrationSteps)
                    : within(s.penetration_max, kReferencePenetration);
    s.restitution = within(s.restitution_error_max, kRestitutionTolerance);
  }
  return s;
}

Stress stress_of(std::span<const Case> cases, const SettingsList& list, WorkPrecision runs) {
  Stress st;
  st.runs = std::move(runs);
  if (!st.runs.complete) return st;

  st.truth.assign(cases.size(), TruthPoint{});
  for (const Row& r : st.runs.reference)
    if (finished(r)) st.truth[r.point] = {r.result.pi1, r.result.impacts};

  const std::vector<std::string> families = families_in_order(cases);
  const std::vector<TruthPoint> no_truth(cases.size());
  summarize_run(st.runs.reference, no_truth, families, st.table);
  const std::size_t n = cases.size();
  for (std::size_t k = 0; k < list.runs.size(); ++k)
    summarize_run(std::span<const Row>(st.runs.points).subspan(k * n, n), st.truth, families, st.table);
  // Grouped by family, the truth first and then the list's settings in their order.
  std::stable_sort(st.table.begin(), st.table.end(), [&](const StressRow& a, const StressRow& b) {
    return std::find(families.begin(), families.end(), a.family) <
           std::find(families.begin(), families.end(), b.family);
  });
  st.complete = true;
  return st;
}

Stress run_stress(std::span<const Case> cases, const SettingsList& list, const SweepOptions& options,
                  int repetitions) {
  return stress_of(cases, list, run_work_precision(cases, list, options, {repetitions, true}));
}

// The columns after `restitution` came later: appended, so that scripts reading columns by
// position keep working, with `accuracy` last.
std::string stability_csv_header() {
  return "family,solver,variant,settings,runs,ok,energy_excess_max,penetration_max,penetration_steps_max,"
         "isolated_impacts,"
         "restitution_error_max,pi1_err_median,pi1_err_max,cpu_median_s,finite,energy,gap,restitution,"
         "pi1_err_p95,impacts,truth_impacts,missed_impact_points,cpu_median_low_s,cpu_median_high_s,accuracy";
}

std::string stability_csv_line(const StressRow& row) {
  std::ostringstream line;
  line << csv_field(row.family) << ',' << csv_field(row.solver) << ',' << csv_field(row.variant) << ','
       << csv_field(row.settings) << ',' << row.runs << ',' << row.ok;
  for (double x : {row.energy_excess_max, row.penetration_max, row.penetration_steps_max})
    line << ',' << format_number(x);
  line << ',' << row.isolated_impacts;
  for (double x : {row.restitution_error_max, row.pi1_err_median, row.pi1_err_max, row.cpu.median})
    line << ',' << format_number(x);
  for (Verdict v : {row.finite, row.energy, row.gap, row.restitution}) line << ',' << name(v);
  line << ',' << format_number(row.pi1_err_p95) << ',' << row.impacts << ',' << row.truth_impacts << ','
       << row.missed_impact_points << ',' << format_number(row.cpu.median_low) << ','
       << format_number(row.cpu.median_high) << ',' << name(row.accuracy);
  return line.str();
}

std::string stress_points_header() { return csv_header() + ",pi1_error"; }

std::string stress_points_line(const Row& row, double pi1_error) {
  return csv_line(row) + "," + format_number(pi1_error);
}

void write_stress_table(std::ostream& out, const Stress& st) {
  out << stability_csv_header() << '\n';
  for (const StressRow& row : st.table) out << stability_csv_line(row) << '\n';
}

void write_stress_points(std::ostream& out, const Stress& st) {
  out << stress_points_header() << '\n';
  const double none = std::numeric_limits<double>::quiet_NaN();
  for (const Row& row : st.runs.reference) out << stress_points_line(row, none) << '\n';
  for (const Row& row : st.runs.points) out << stress_points_line(row, pi1_error(row, st.truth[row.point].pi1)) << '\n';
}

}  // namespace pb
