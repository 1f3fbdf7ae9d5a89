#include "app/workprecision_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <stdexcept>

#include "app/check_report.hpp"
#include "output/output_files.hpp"
#include "output/resumable_sweep.hpp"
#include "cases/text.hpp"
#include "frontend/errors.hpp"
#include "studies/workprecision.hpp"

namespace pb::app {

namespace {

// Points named in one failing row's line: enough to start looking, short enough to read.
constexpr std::size_t kListedPoints = 5;

std::string row_key(const std::string& family, const std::string& solver, const std::string& variant,
                    const std::string& settings) {
  return family + '\n' + solver + '\n' + variant + '\n' + settings;
}

// "point 3 diverged, point 7 step_cap" for the first kListedPoints of `runs`, "and N more" after.
template <typename Describe>
std::string listed(const std::vector<const Row*>& runs, Describe describe) {
  std::string text;
  for (std::size_t i = 0; i < runs.size() && i < kListedPoints; ++i)
    text += (i ? ", " : "") + std::string("point ") + std::to_string(runs[i]->point) + " " + describe(*runs[i]);
  if (runs.size() > kListedPoints) text += " and " + std::to_string(runs.size() - kListedPoints) + " more";
  return text;
}

// --check: a verdict per row, failing for a run that did not finish ok, or an error above
// --max-error (err_median) or --max-error-p95 (err_p95); the line names the points: those
// that did not finish with their status, and those above the bound, worst first.
std::vector<Verdict> verdicts(const WorkPrecision& wp, const WorkPrecisionFlags& flags) {
  std::map<std::string, std::vector<const Row*>> runs;
  for (const Row& r : wp.points) runs[row_key(r.input.family, r.solver, r.variant, r.settings)].push_back(&r);
  const auto error = [&](const Row& r) {
    return std::abs(r.result.pi1 - wp.reference[r.point].result.pi1) / wp.reference[r.point].result.pi1;
  };
  std::vector<Verdict> out;
  for (const WorkPrecisionRow& row : wp.table) {
    std::string problem = work_precision_problem(row, flags.max_error, flags.max_error_p95);
    if (!problem.empty()) {
      const std::vector<const Row*>& mine = runs[row_key(row.family, row.solver, row.variant, row.settings)];
      std::vector<const Row*> failed, above;
      const double bound = std::fmin(flags.max_error, flags.max_error_p95);  // NaN only when neither is given
      for (const Row* r : mine) {
        if (r->result.status != Status::ok || !std::isfinite(r->result.pi1))
          failed.push_back(r);
        else if (!std::isnan(bound) && !(error(*r) <= bound))
          above.push_back(r);
      }
      std::stable_sort(above.begin(), above.end(), [&](const Row* a, const Row* b) { return error(*a) > error(*b); });
      if (!failed.empty())
        problem += " (" + listed(failed, [](const Row& r) { return std::string(name(r.result.status)); }) + ")";
      if (!above.empty())
        problem += "; above " + format_number(bound) + ": " + listed(above, [&](const Row& r) {
                     char text[32];
                     std::snprintf(text, sizeof text, "(%.3g)", error(r));
                     return std::string(text);
                   });
    }
    out.push_back({"workprecision", row_label(row), problem});
  }
  return out;
}

}  // namespace

CLI::App* add_workprecision_command(CLI::App& app, WorkPrecisionFlags& flags) {
  CLI::App* command = add_study_command(
      app, flags, "workprecision", "Relative Pi1 error against CPU time per run, per family and solver setting",
      "Also write every run's row (spectrum columns) to this file",
      "Exit 1 when a run did not finish ok, or a setting's err_median is above --max-error or its err_p95 above "
      "--max-error-p95 (after writing the outputs), naming each failing row and its points on stderr");
  command->add_option("--max-error", flags.max_error,
                      "With --check: the largest err_median a setting may have in a family (relative)");
  command->add_option("--max-error-p95", flags.max_error_p95,
                      "With --check: the largest err_p95 (95th percentile) a setting may have in a family (relative)");
  const std::size_t before = command->get_options().size();
  add_case_flags(*command, flags.case_flags);
  const std::vector<CLI::Option*> options = command->get_options();
  flags.case_options.assign(options.begin() + static_cast<std::ptrdiff_t>(before), options.end());
  return command;
}

int workprecision_command(const CLI::App& command, const WorkPrecisionFlags& flags, const Processes& processes) {
  processes.agree([&] {
    for (const auto& [flag, value] :
         {std::pair{"--max-error", flags.max_error}, {"--max-error-p95", flags.max_error_p95}}) {
      if (!command.count(flag)) continue;
      if (!(value >= 0.0 && std::isfinite(value))) throw BadInput(std::string(flag) + ": must be a finite number >= 0");
      if (!flags.check) throw BadInput(std::string(flag) + ": needs --check");
    }
  }, exit_code_of);
  const auto case_from_flags = [&] {
    CaseSet set{"case", "the case given by flags", {chosen_case(command, flags.case_flags).input}};
    set.cases.front().family = "case";
    return set;
  };
  processes.agree([&] {
    for (const CLI::Option* option : flags.case_options)
      if (option->count() && !flags.case_set.empty())
        throw BadInput(option->get_name() + ": not with CASESET (give the case by a case-set file or by flags)");
  }, exit_code_of);
  Study study = run_study(command, flags, "workprecision", {.model_references = true}, processes, case_from_flags);
  if (!study.rows) return kInterrupted;
  if (!processes.leader()) return 0;
  const WorkPrecision wp = work_precision_of(study.set.cases, study.list, std::move(*study.rows), true);

  std::size_t failed_runs = 0, failed_rows = 0;
  for (const std::vector<Row>* rows : {&wp.reference, &wp.points})
    for (const Row& r : *rows) failed_runs += r.result.status != Status::ok ? 1 : 0;
  for (const WorkPrecisionRow& row : wp.table) failed_rows += row.summary.failed > 0 ? 1 : 0;
  write_study(
      flags, study,
      [&](std::ostream& out) { write_work_precision_points(out, wp); },
      [&](std::ostream& out) { write_work_precision_table(out, wp); }, failed_runs, failed_rows);
  return flags.check ? report_check("workprecision", verdicts(wp, flags), "rows", flags.junit) : 0;
}

}  // namespace pb::app
