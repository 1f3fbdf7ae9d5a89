#include "studies/workprecision.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <sstream>
#include <tuple>

#include "cases/text.hpp"
#include "studies/stats.hpp"
#include "solvers/registry.hpp"

namespace pb {

namespace {

std::string run_key(const SweepRun& run) {
  return std::string(run.solver->name) + " " + run.solver->describe(run.settings);
}

// Where each list run's model reference is among list.runs followed by `extra`
// (model_reference_runs): its index, or -1.
std::vector<int> model_reference_index(const SettingsList& list, const std::vector<SweepRun>& extra) {
  std::vector<std::string> keys;
  for (const SweepRun& run : list.runs) keys.push_back(run_key(run));
  for (const SweepRun& run : extra) keys.push_back(run_key(run));
  std::vector<int> index;
  for (const SweepRun& run : list.runs) {
    index.push_back(-1);
    if (!run.solver->model_reference) continue;
    const std::optional<ModelReference> ref = run.solver->model_reference(run.settings);
    if (!ref) continue;
    const SweepRun own{find_solver(ref->solver), ref->settings, 1};
    if (!own.solver) continue;
    const auto at = std::find(keys.begin(), keys.end(), run_key(own));
    if (at != keys.end()) index.back() = static_cast<int>(at - keys.begin());
  }
  return index;
}

}  // namespace

std::vector<SweepRun> model_reference_runs(const SettingsList& list) {
  std::vector<std::string> keys;
  for (const SweepRun& run : list.runs) keys.push_back(run_key(run));
  std::vector<SweepRun> out;
  for (const SweepRun& run : list.runs) {
    if (!run.solver->model_reference) continue;
    const std::optional<ModelReference> ref = run.solver->model_reference(run.settings);
    if (!ref) continue;
    SweepRun own{find_solver(ref->solver), ref->settings, 1};
    if (!own.solver) continue;  // a reference left out of this build
    own.settings.time_limit = list.reference_time_limit;
    const std::string key = run_key(own);
    if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
    keys.push_back(key);
    out.push_back(own);
  }
  return out;
}

std::vector<SweepRun> study_runs(const SettingsList& list, const StudyOptions& study) {
  std::vector<SweepRun> runs;
  SweepRun truth{&reference_solver(), {}, study.repetitions};
  truth.settings.tol_scale = list.reference_tol_scale;
  truth.settings.time_limit = list.reference_time_limit;
  runs.push_back(truth);
  for (const SweepRun& run : list.runs) {
    runs.push_back({run.solver, run.settings, study.repetitions, study.monitor, study.estimate});
    runs.back().settings.monitor = study.monitor && run.settings.monitor;
  }
  if (study.model_references)
    for (SweepRun run : model_reference_runs(list)) {
      run.repetitions = study.repetitions;
      run.settings.monitor = false;
      runs.push_back(run);
    }
  return runs;
}

WorkPrecision work_precision_of(std::span<const Case> cases, const SettingsList& list, std::vector<Row> rows,
                                bool model_references) {
  WorkPrecision wp;
  const std::size_t n = cases.size();
  const std::vector<SweepRun> extra = model_references ? model_reference_runs(list) : std::vector<SweepRun>{};
  std::vector<SweepRun> all = list.runs;
  all.insert(all.end(), extra.begin(), extra.end());
  if (rows.size() != n * (all.size() + 1)) return wp;
  wp.reference.assign(std::make_move_iterator(rows.begin()), std::make_move_iterator(rows.begin() + n));
  wp.points.assign(std::make_move_iterator(rows.begin() + n), std::make_move_iterator(rows.end()));
  std::vector<double> reference(n);
  for (const Row& r : wp.reference) reference[r.point] = r.result.pi1;
  std::vector<int> own = model_references ? model_reference_index(list, extra) : std::vector<int>{};
  own.resize(all.size(), -1);

  const std::vector<std::string> families = families_in_order(cases);
  const auto rows_of = [&](std::size_t k) { return std::span<const Row>(wp.points).subspan(k * n, n); };
  for (std::size_t k = 0; k < all.size(); ++k) {
    const SweepRun& run = all[k];
    for (const std::string& family : families) {
      std::vector<const Row*> mine;
      std::vector<double> ref, model;
      for (const Row& r : rows_of(k)) {
        if (r.input.family != family) continue;
        mine.push_back(&r);
        ref.push_back(reference[r.point]);
        if (own[k] >= 0) model.push_back(rows_of(static_cast<std::size_t>(own[k]))[r.point].result.pi1);
      }
      WorkPrecisionRow row{family, std::string(run.solver->name), run.settings.variant,
                           run.solver->describe(run.settings), summarize(mine, ref), {}, {}, {}};
      if (k < list.physical.size()) row.physical = list.physical[k];
      if (own[k] >= 0) {
        const SweepRun& m = all[static_cast<std::size_t>(own[k])];
        row.model_reference = std::string(m.solver->name) + " " + m.solver->describe(m.settings);
        row.integration = summarize(mine, model);
      }
      wp.table.push_back(std::move(row));
    }
  }
  // Table rows grouped by family, settings in list order within each.
  std::stable_sort(wp.table.begin(), wp.table.end(), [&](const WorkPrecisionRow& a, const WorkPrecisionRow& b) {
    return std::find(families.begin(), families.end(), a.family) < std::find(families.begin(), families.end(), b.family);
  });
  wp.complete = true;
  return wp;
}

WorkPrecision run_work_precision(std::span<const Case> cases, const SettingsList& list, const SweepOptions& options,
                                 const StudyOptions& study) {
  return work_precision_of(cases, list, run_sweep(cases, study_runs(list, study), options), study.model_references);
}

std::string work_precision_csv_header() {
  return "family,solver,variant,settings,points,failed,err_median,err_p95,err_max,cpu_median_s,cpu_mean_s,"
         "cpu_median_low_s,cpu_median_high_s,repetitions,model_reference,int_err_median,int_err_p95,int_err_max,"
         "unresolved,cost,h_s,k_contact";
}

std::string work_precision_csv_line(const WorkPrecisionRow& row) {
  const Summary& s = row.summary;
  std::ostringstream line;
  line << csv_field(row.family) << ',' << csv_field(row.solver) << ',' << csv_field(row.variant) << ','
       << csv_field(row.settings) << ',' << s.points << ',' << s.failed;
  for (double x : {s.err_median, s.err_p95, s.err_max, s.cpu.median, s.cpu.mean, s.cpu.median_low, s.cpu.median_high})
    line << ',' << format_number(x);
  line << ',' << s.cpu.repetitions << ',' << csv_field(row.model_reference);
  for (double x : {row.integration.err_median, row.integration.err_p95, row.integration.err_max})
    line << ',' << format_number(x);
  // The cost's clock, one for every solver since issue 48 (older files may say solve_seconds).
  line << ',' << s.unresolved << ",cpu_seconds";
  for (double x : {row.physical.h_s, row.physical.k_contact}) line << ',' << (x > 0.0 ? format_number(x) : "");
  return line.str();
}

std::string work_precision_problem(const WorkPrecisionRow& row, double max_error, double max_error_p95) {
  const Summary& s = row.summary;
  std::string problem;
  if (s.failed > 0)
    problem = std::to_string(s.failed) + " of " + std::to_string(s.points) + " runs did not finish ok";
  if (s.unresolved > 0)
    problem += (problem.empty() ? "" : "; ") + std::to_string(s.unresolved) + " of " + std::to_string(s.points) +
               " runs finished without resolving what they solved (kit/verdict.hpp)";
  for (const auto& [bound, value, column] :
       {std::tuple{max_error, s.err_median, "err_median"}, std::tuple{max_error_p95, s.err_p95, "err_p95"}})
    if (!std::isnan(bound) && !(value <= bound))
      problem += (problem.empty() ? "" : "; ") + std::string(column) + " " +
                 (std::isnan(value) ? "empty (no run finished)" : format_number(value)) + " above " +
                 format_number(bound);
  return problem;
}

void write_work_precision_table(std::ostream& out, const WorkPrecision& wp) {
  out << work_precision_csv_header() << '\n';
  for (const WorkPrecisionRow& row : wp.table) out << work_precision_csv_line(row) << '\n';
}

void write_work_precision_points(std::ostream& out, const WorkPrecision& wp) {
  write_csv(out, wp.reference);
  for (const Row& row : wp.points) out << csv_line(row) << '\n';
}

}  // namespace pb
