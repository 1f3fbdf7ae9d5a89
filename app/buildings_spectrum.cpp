#include "app/buildings_spectrum.hpp"

#include <cstdlib>
#include <string>
#include <thread>

#include "frontend/buildings_run.hpp"
#include "frontend/errors.hpp"
#include "output/output_files.hpp"
#include "output/sweep_watch.hpp"
#include "sweep/buildings_sweep.hpp"

namespace pb::app {

int buildings_spectrum(const CLI::App& command, const SpectrumFlags& flags, const BuildingsSet& set) {
  const auto given = [&](std::string_view flag) { return command.count(std::string(flag)) > 0; };
  const SolverInfo& solver = check_buildings_solver(flags.solver_flags, given);
  for (std::string_view flag : {"--repetitions", "--estimate-error", "--target-error", "--junit", "--monitor"})
    if (given(flag)) throw BadInput(std::string(flag) + ": not for the buildings scene (yet)");
  if (given("--threads") && flags.threads == 0) throw BadInput("--threads: must be >= 1");
  if (set.points.empty()) throw BadInput(flags.case_set + ": no cases");
  if (!flags.out.empty()) {
    std::vector<NamedFile> inputs = {{"CASESET", flags.case_set}};
    for (const BuildingCase& c : set.points)
      if (!c.record.empty()) inputs.push_back({"record", c.record});
    check_outputs_apart({{"--out", flags.out}}, inputs);
    check_sweep_output(flags.out, "--out");
  }

  const unsigned threads = flags.threads ? flags.threads : std::max(1u, std::thread::hardware_concurrency());
  SweepWatch watch("spectrum", "points", set.points.size(), 0, progress_on_stderr(true),
                   [] { std::_Exit(kInterrupted); });
  const auto points = sweep_buildings(set.points, solver, flags.solver_flags.settings, static_cast<int>(threads),
                                      watch.cancel(), [&](std::size_t done) { watch.set_done(done); });
  watch.finish();
  if (!points) return kInterrupted;

  const std::string settings = solver.describe(flags.solver_flags.settings);
  std::size_t failed = 0, rows = 0;
  std::string text = buildings_csv_header();
  for (std::size_t i = 0; i < points->size(); ++i) {
    append_buildings_rows(text, set.points[i], i, solver.name, settings, (*points)[i]);
    if ((*points)[i].result.status != Status::ok) ++failed;
    for (const Building& b : set.points[i].scene.buildings) rows += static_cast<std::size_t>(b.floors());
  }
  const auto csv = [&](std::ostream& out) { out << text; };
  if (flags.out.empty())
    write_to_stdout(csv);
  else
    write_atomically(flags.out, csv);
  report_written(rows, flags.out, failed ? failed_note(failed, "points", flags.check) : "");
  return flags.check && failed ? 1 : 0;
}

}  // namespace pb::app
