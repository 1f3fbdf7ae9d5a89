#include "app/separation_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "cases/buildings_set.hpp"
#include "cases/case_set.hpp"
#include "frontend/errors.hpp"
#include "output/output_files.hpp"
#include "output/sweep_watch.hpp"
#include "solvers/registry.hpp"
#include "studies/separation_study.hpp"
#include "sweep/buildings_sweep.hpp"
#include "sweep/sweep.hpp"

namespace pb::app {

namespace {

// The reference over the cases, with progress; nullopt when interrupted.
std::optional<std::vector<Row>> solve_all(const std::vector<Case>& cases, unsigned threads, std::size_t done_before,
                                          std::size_t total) {
  SweepWatch watch("separation", "solves", total, done_before, progress_on_stderr(true),
                   [] { std::_Exit(kInterrupted); });
  SweepOptions options;
  options.threads = threads;
  options.cancel = &watch.cancel();
  options.on_progress = [&](std::size_t done, std::size_t) { watch.set_done(done_before + done); };
  std::vector<Row> rows = run_sweep(cases, reference_solver(), Settings{}, options);
  watch.finish();
  if (watch.interrupted() || rows.size() < cases.size()) return std::nullopt;
  return rows;
}

// The outputs, checked apart from the inputs (the case set and its records).
std::vector<NamedFile> separation_outputs(const SeparationFlags& flags, std::vector<NamedFile> inputs) {
  std::vector<NamedFile> outputs;
  if (!flags.out.empty()) {
    check_sweep_output(flags.out, "--out");
    outputs.push_back({"--out", flags.out});
  }
  if (!flags.summary.empty()) {
    check_sweep_output(flags.summary, "--summary");
    outputs.push_back({"--summary", flags.summary});
  }
  inputs.push_back({"CASESET", flags.case_set});
  check_outputs_apart(outputs, inputs);
  return outputs;
}

// The reference over the points (a pass of sweep_reference), with progress; nullopt when
// interrupted.
// The study's files, each whole or not at all: the summary where --summary asks (made only
// then), and the table of `rows` rows to --out or stdout.
void write_outputs(const SeparationFlags& flags, const std::function<void(std::ostream&)>& table, std::size_t rows,
                   const std::function<std::vector<RuleSummary>()>& summarise) {
  if (!flags.summary.empty()) {
    const std::vector<RuleSummary> summary = summarise();
    write_atomically(flags.summary, [&](std::ostream& out) { write_rule_summary(out, summary); });
    report_written(summary.size(), flags.summary);
  }
  if (flags.out.empty()) {
    write_to_stdout(table);
  } else {
    write_atomically(flags.out, table);
    report_written(rows, flags.out);
  }
}

std::optional<std::vector<buildings::BuildingsResult>> solve_points(std::span<const BuildingCase> points,
                                                                    ReferencePass pass, unsigned threads,
                                                                    std::size_t done_before, std::size_t total) {
  SweepWatch watch("separation", "solves", total, done_before, progress_on_stderr(true),
                   [] { std::_Exit(kInterrupted); });
  auto out = sweep_reference(points, pass, static_cast<int>(threads), watch.cancel(),
                             [&](std::size_t done) { watch.set_done(done_before + done); });
  watch.finish();
  return out;
}

// A buildings set: a row per contact (floor level) of every point, from the reference's free
// watch; with --gap-fractions every point again with contacts at those fractions of its gap.
int buildings_separation_command(const SeparationFlags& flags, const BuildingsSet& set) {
  if (set.points.empty()) throw BadInput(flags.case_set + ": no cases");
  std::vector<NamedFile> inputs;
  for (const BuildingCase& c : set.points)
    if (!c.record.empty()) inputs.push_back({"record", c.record});
  separation_outputs(flags, inputs);
  const unsigned threads = flags.threads ? flags.threads : std::max(1u, std::thread::hardware_concurrency());
  const std::size_t total = set.points.size() * (1 + flags.gap_fractions.size());
  const auto free = solve_points(set.points, ReferencePass::free_motion, threads, 0, total);
  if (!free) return kInterrupted;
  std::vector<BuildingsSeparation> found;
  found.reserve(free->size());
  std::size_t rows = 0;
  for (std::size_t i = 0; i < free->size(); ++i) {
    found.push_back(buildings_separation(set.points[i].scene, (*free)[i]));
    rows += found.back().floors.size();
  }
  std::vector<buildings::BuildingsResult> at_fraction;
  if (!flags.gap_fractions.empty()) {
    const std::vector<BuildingCase> again = buildings_fraction_points(set.points, found, flags.gap_fractions);
    auto more = solve_points(again, ReferencePass::with_contacts, threads, set.points.size(), total);
    if (!more) return kInterrupted;
    at_fraction = std::move(*more);
  }
  const auto table = [&](std::ostream& out) {
    write_buildings_separation_table(out, set.points, found, at_fraction, flags.gap_fractions);
  };
  write_outputs(flags, table, rows, [&] {
    const std::vector<RuleRatios> ratios = buildings_rule_ratios(set.points, found);
    return summarise_rules(std::span<const RuleRatios>(ratios));
  });
  return 0;
}

}  // namespace

CLI::App* add_separation_command(CLI::App& app, SeparationFlags& flags) {
  CLI::App* command = app.add_subcommand(
      "separation", "The gap that avoids pounding against the rules (ABS, SRSS, DDC) over a case set");
  command->add_option("CASESET", flags.case_set,
                      "Case-set file (neighbours: wall, pair or row3; or a buildings set, a row per floor level)")
      ->required();
  command->add_option("--out", flags.out, "Write the per-case table here (CSV; default: stdout)");
  command->add_option("--summary", flags.summary,
                      "Write each rule's ratio to the required gap per family (median, 16/84 %, unconservative share)");
  command->add_option("--gap-fractions", flags.gap_fractions,
                      "Solve each case again at these fractions of its required gap (e.g. 0.25,0.5,0.75): the "
                      "amplification of the peak")
      ->delimiter(',');
  command->add_option("--threads", flags.threads, "Worker threads (default: every core)");
  return command;
}

int separation_command(const SeparationFlags& flags) {
  for (const double f : flags.gap_fractions)
    if (!(std::isfinite(f) && f > 0.0 && f < 1.0))
      throw BadInput("--gap-fractions: each must be in (0, 1) (a fraction of the required gap), got " +
                     std::to_string(f));
  std::optional<BuildingsSet> buildings;
  try {
    buildings = load_buildings_set(flags.case_set);
  } catch (const CaseSetError& e) {
    throw BadInput(e.what());
  }
  if (buildings) return buildings_separation_command(flags, *buildings);
  CaseSet set;
  try {
    set = load_case_set(flags.case_set);
  } catch (const CaseSetError& e) {
    throw BadInput(e.what());
  }
  if (set.cases.empty()) throw BadInput(flags.case_set + ": no cases");
  for (std::size_t i = 0; i < set.cases.size(); ++i)
    if (set.cases[i].scene == Scene::chain)
      throw BadInput(flags.case_set + ": point " + std::to_string(i) +
                     ": scene chain (a kicked row, not neighbours under a load): `separation` takes wall, pair, row3");
  separation_outputs(flags, record_files(set.cases));
  const std::size_t total = set.cases.size() * (1 + flags.gap_fractions.size());
  const std::optional<std::vector<Row>> given = solve_all(set.cases, flags.threads, 0, total);
  if (!given) return kInterrupted;
  std::vector<Row> at_fraction;
  if (!flags.gap_fractions.empty()) {
    const std::optional<std::vector<Row>> more =
        solve_all(fraction_cases(*given, flags.gap_fractions), flags.threads, given->size(), total);
    if (!more) return kInterrupted;
    at_fraction = std::move(*more);
  }
  const auto table = [&](std::ostream& out) { write_separation_table(out, *given, at_fraction, flags.gap_fractions); };
  write_outputs(flags, table, given->size(), [&] { return summarise_rules(*given); });
  return 0;
}

}  // namespace pb::app
