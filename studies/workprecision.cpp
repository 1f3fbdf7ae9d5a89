#include "studies/workprecision.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pb {

namespace {

std::vector<std::string> families_in_order(std::span<const Case> cases) {
  std::vector<std::string> out;
  for (const Case& c : cases)
    if (std::find(out.begin(), out.end(), c.family) == out.end()) out.push_back(c.family);
  return out;
}

}  // namespace

std::vector<SweepRun> study_runs(const SettingsList& list, const StudyOptions& study) {
  std::vector<SweepRun> runs;
  SweepRun truth{&reference_solver(), {}, study.repetitions};
  truth.settings.tol_scale = list.reference_tol_scale;
  truth.settings.time_limit = list.reference_time_limit;
  runs.push_back(truth);
  for (const SweepRun& run : list.runs) {
    runs.push_back({run.solver, run.settings, study.repetitions});
    runs.back().settings.monitor = study.monitor && run.settings.monitor;
  }
  return runs;
}

WorkPrecision work_precision_of(std::span<const Case> cases, const SettingsList& list, std::vector<Row> rows) {
  WorkPrecision wp;
  const std::size_t n = cases.size();
  if (rows.size() != n * (list.runs.size() + 1)) return wp;
  wp.reference.assign(std::make_move_iterator(rows.begin()), std::make_move_iterator(rows.begin() + n));
  wp.points.assign(std::make_move_iterator(rows.begin() + n), std::make_move_iterator(rows.end()));
  std::vector<double> reference(n);
  for (const Row& r : wp.reference) reference[r.point] = r.result.pi1;

  const std::vector<std::string> families = families_in_order(cases);
  for (std::size_t k = 0; k < list.runs.size(); ++k) {
    const SweepRun& run = list.runs[k];
    const std::span<const Row> run_rows = std::span<const Row>(wp.points).subspan(k * n, n);
    for (const std::string& family : families) {
      std::vector<const Row*> mine;
      std::vector<double> ref;
      for (const Row& r : run_rows) {
        if (r.input.family != family) continue;
        mine.push_back(&r);
        ref.push_back(reference[r.point]);
      }
      wp.table.push_back({family, std::string(run.solver->name), run.settings.variant,
                          run.solver->describe(run.settings), summarize(mine, ref)});
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
  return work_precision_of(cases, list, run_sweep(cases, study_runs(list, study), options));
}

std::string work_precision_csv_header() {
  return "family,solver,variant,settings,points,failed,err_median,err_p95,err_max,cpu_median_s,cpu_mean_s,"
         "cpu_median_low_s,cpu_median_high_s,repetitions";
}

std::string work_precision_csv_line(const WorkPrecisionRow& row) {
  const Summary& s = row.summary;
  std::ostringstream line;
  line << csv_field(row.family) << ',' << csv_field(row.solver) << ',' << csv_field(row.variant) << ','
       << csv_field(row.settings) << ',' << s.points << ',' << s.failed;
  for (double x : {s.err_median, s.err_p95, s.err_max, s.cpu.median, s.cpu.mean, s.cpu.median_low, s.cpu.median_high})
    line << ',' << format_number(x);
  line << ',' << s.cpu.repetitions;
  return line.str();
}

std::string work_precision_problem(const WorkPrecisionRow& row, double max_error) {
  const Summary& s = row.summary;
  std::string problem;
  if (s.failed > 0)
    problem = std::to_string(s.failed) + " of " + std::to_string(s.points) + " runs did not finish ok";
  if (!std::isnan(max_error) && !(s.err_median <= max_error))
    problem += (problem.empty() ? "" : "; ") + std::string("err_median ") +
               (std::isnan(s.err_median) ? "empty (no run finished)" : format_number(s.err_median)) +
               " above " + format_number(max_error);
  return problem;
}

}  // namespace pb
