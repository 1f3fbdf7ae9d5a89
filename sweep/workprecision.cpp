#include "sweep/workprecision.hpp"

#include <algorithm>
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

WorkPrecision run_work_precision(std::span<const Case> cases, const SettingsList& list, const SweepOptions& options) {
  WorkPrecision wp;
  const std::size_t total = cases.size() * (list.runs.size() + 1);
  std::size_t done_before = 0;
  SweepOptions opt = options;
  opt.on_progress = [&](std::size_t done, std::size_t) {
    if (options.on_progress) options.on_progress(done_before + done, total);
  };
  auto cancelled = [&] { return options.cancel && options.cancel->load(); };

  Settings truth;
  truth.tol_scale = list.reference_tol_scale;
  truth.time_limit = list.reference_time_limit;
  wp.reference = run_sweep(cases, *find_solver("event-driven"), truth, opt);
  if (cancelled()) return wp;
  done_before += cases.size();
  std::vector<double> reference(cases.size());
  for (const Row& r : wp.reference) reference[r.point] = r.result.pi1;

  const std::vector<std::string> families = families_in_order(cases);
  for (const RunSpec& run : list.runs) {
    const SolverInfo& solver = *find_solver(run.solver);
    std::vector<Row> rows = run_sweep(cases, solver, run.settings, opt);
    if (cancelled()) return wp;
    done_before += cases.size();
    for (const std::string& family : families) {
      std::vector<const Row*> mine;
      std::vector<double> ref;
      for (const Row& r : rows) {
        if (r.input.family != family) continue;
        mine.push_back(&r);
        ref.push_back(reference[r.point]);
      }
      wp.table.push_back({family, run.solver, run.settings.variant, solver.describe(run.settings), summarize(mine, ref)});
    }
    wp.points.insert(wp.points.end(), std::make_move_iterator(rows.begin()), std::make_move_iterator(rows.end()));
  }
  // Table rows grouped by family, settings in list order within each.
  std::stable_sort(wp.table.begin(), wp.table.end(), [&](const WorkPrecisionRow& a, const WorkPrecisionRow& b) {
    return std::find(families.begin(), families.end(), a.family) < std::find(families.begin(), families.end(), b.family);
  });
  wp.complete = true;
  return wp;
}

std::string work_precision_csv_header() {
  return "family,solver,variant,settings,points,failed,err_median,err_p95,err_max,cpu_median_s,cpu_mean_s";
}

std::string work_precision_csv_line(const WorkPrecisionRow& row) {
  const Summary& s = row.summary;
  std::ostringstream line;
  line << csv_field(row.family) << ',' << csv_field(row.solver) << ',' << csv_field(row.variant) << ','
       << csv_field(row.settings) << ',' << s.points << ',' << s.failed;
  for (double x : {s.err_median, s.err_p95, s.err_max, s.cpu_median, s.cpu_mean}) line << ',' << format_number(x);
  return line.str();
}

}  // namespace pb
