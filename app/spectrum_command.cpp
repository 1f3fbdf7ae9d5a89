#include "app/spectrum_command.hpp"

#include <algorithm>
#include <array>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "app/buildings_spectrum.hpp"
#include "app/check_report.hpp"
#include "output/output_files.hpp"
#include "output/partial_output.hpp"
#include "output/resumable_sweep.hpp"
#include "app/study_run.hpp"
#include "output/sweep_watch.hpp"
#include "cases/buildings_set.hpp"
#include "cases/case_set.hpp"
#include "frontend/case_flags.hpp"
#include "frontend/errors.hpp"
#include "sweep/sweep.hpp"

namespace pb::app {

namespace {

// --check: a verdict per family, failing when a point of it did not finish ok; the line
// names the first few such points, their status and the first one's message. Fed the rows in
// point order, one at a time (the rows are not held: output/partial_output.hpp).
class FamilyVerdicts {
 public:
  void add(const std::string& family, std::size_t point, std::string_view status, const std::string& message) {
    auto at = std::find_if(families_.begin(), families_.end(), [&](const Family& f) { return f.name == family; });
    if (at == families_.end()) {
      families_.emplace_back();
      families_.back().name = family;
      at = families_.end() - 1;
    }
    ++at->points;
    if (status == name(Status::ok)) return;
    if (at->failed++ == 0) at->first_message = message;
    if (at->listed.size() < kListedPoints) at->listed.push_back("point " + std::to_string(point) + " " + std::string(status));
  }
  std::size_t failed() const {
    std::size_t n = 0;
    for (const Family& f : families_) n += f.failed;
    return n;
  }
  std::vector<Verdict> verdicts() const {
    std::vector<Verdict> out;
    for (const Family& f : families_) {
      std::string failure;
      if (f.failed) {
        failure = std::to_string(f.failed) + " of " + std::to_string(f.points) + " points did not finish ok (";
        for (std::size_t i = 0; i < f.listed.size(); ++i) failure += (i ? ", " : "") + f.listed[i];
        if (f.failed > kListedPoints) failure += " and " + std::to_string(f.failed - kListedPoints) + " more";
        failure += ")";
        if (!f.first_message.empty()) failure += "; the first: " + f.first_message;
      }
      out.push_back({"spectrum", "family " + f.name, failure});
    }
    return out;
  }

 private:
  static constexpr std::size_t kListedPoints = 5;
  struct Family {
    std::string name;
    std::size_t points = 0, failed = 0;
    std::vector<std::string> listed;
    std::string first_message;
  };
  std::vector<Family> families_;
};

// The output, from the partial file's lines in point order (output/partial_output.hpp).
void write_final(const SpectrumFlags& flags, const std::string& partial, std::size_t points,
                 FamilyVerdicts& verdicts) {
  const auto csv = [&](std::ostream& out) {
    // The columns looked up once, and a message read only where a point did not finish ok: a
    // lookup by name and the scan to the message per point were a tenth of this serial pass.
    std::optional<std::array<std::size_t, 4>> at;  // family, point, status, message
    write_from_partial(partial, points, out, [&](const PartialRecord& r) {
      if (!at) at = {r.index("family"), r.index("point"), r.index("status"), r.index("message")};
      const auto [family, point, status, message] = *at;
      const std::string s = r.field(status);
      verdicts.add(r.field(family), static_cast<std::size_t>(std::stoull(r.field(point))), s,
                   s == name(Status::ok) ? std::string() : r.field(message));
    });
  };
  if (flags.out.empty())
    write_to_stdout(csv);
  else
    write_atomically(flags.out, csv);
}

}  // namespace

CLI::App* add_spectrum_command(CLI::App& app, SpectrumFlags& flags) {
  CLI::App* command =
      app.add_subcommand("spectrum", "Solve every case of a case-set file; one CSV row per case, in point order");
  command->add_option("CASESET", flags.case_set, "Case-set file (TOML, see cases/README.md)")->required();
  add_solver_flags(*command, flags.solver_flags);
  command->add_option("--out", flags.out, "Write the CSV to this file (default: stdout)");
  command->add_option("--threads", flags.threads, "Worker threads (default: all cores)");
  add_repetitions_flag(*command, flags.repetitions);
  add_estimate_flags(*command, flags.estimate, true);
  command->add_flag(
      "--check", flags.check,
      "Exit 1 when a point did not finish ok (after writing the output), naming them on stderr per family");
  add_junit_flag(*command, flags.junit, "family");
  return command;
}

int spectrum_command(const CLI::App& command, const SpectrumFlags& flags, const Processes& processes) {
  // A buildings set has rows of its own, one per floor (app/buildings_spectrum.hpp), and is
  // swept by one process.
  std::optional<BuildingsSet> buildings;
  processes.agree([&] {
    buildings = load_buildings_set(flags.case_set);
    if (buildings && processes.count() > 1)
      throw BadInput("buildings: a buildings sweep runs in one process (start it without mpiexec)");
  }, exit_code_of);
  if (buildings) return buildings_spectrum(command, flags, *buildings);
  // Everything is checked before the first file is created.
  CaseListSet set;  // built on demand: a million points held 320 MB of cases
  std::vector<SweepRun> runs(1);
  EarlierRows earlier;  // which points are done: the rows stay in the partial file
  const std::string partial = partial_file_name(flags.out, "spectrum");
  OutputLock lock;  // held until the output is written and the partial file removed
  processes.agree([&] {
    set = load_case_list(flags.case_set);
    validate_case_set(set.cases, flags.case_set);
    check_estimate_flags(command, flags.estimate, true);
    runs[0] = {&checked_solver(flags.solver_flags, command), flags.solver_flags.settings, flags.repetitions, false,
               flags.estimate};
    if (command.count("--threads") && flags.threads == 0) throw BadInput("--threads: must be >= 1");
    if (!processes.leader()) return;
    std::vector<NamedFile> inputs = record_files(set.cases);
    inputs.push_back({"CASESET", flags.case_set});
    // --junit is an output like --out: never an input, the partial file or --out itself.
    check_outputs_apart({{"--out", flags.out}, {"--junit", flags.junit}}, inputs, partial,
                        lock_file_name(flags.out, "spectrum"));
    if (!flags.out.empty()) check_sweep_output(flags.out, "--out");
    check_junit_target(flags.junit, flags.check);
    lock = take_output_lock(flags.out, "spectrum", partial);
    earlier = read_earlier_rows(partial, set.cases, runs, false);
  }, exit_code_of);

  const auto rows = run_resumable("spectrum", processes, set.cases, runs, partial, lock, std::move(earlier),
                                  flags.threads, nullptr, false);
  if (!rows) return kInterrupted;
  if (!processes.leader()) return 0;
  FamilyVerdicts verdicts;
  write_outputs(partial, [&] { write_final(flags, partial, set.cases.size(), verdicts); });
  const std::size_t failed = verdicts.failed();
  report_written(set.cases.size(), flags.out, failed ? failed_note(failed, "points", flags.check) : "");
  return flags.check ? report_check("spectrum", verdicts.verdicts(), "families", flags.junit) : 0;
}

}  // namespace pb::app
