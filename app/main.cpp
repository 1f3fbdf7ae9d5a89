// poundbench: the command line. Exit codes: 0 done, 1 runtime failure, 2 bad input (one
// line on stderr naming the flag or file, the field and the reason), 130 interrupted.
// Under an MPI launcher every rank runs this; only the leader (rank 0) prints, and the
// sweep commands share their work among the ranks (sweep/processes.hpp).

#include <algorithm>
#include <exception>
#include <iostream>
#include <memory>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "app/baseline_command.hpp"
#include "app/errors.hpp"
#include "app/run_command.hpp"
#include "app/spectrum_command.hpp"
#include "app/stress_command.hpp"
#include "app/workprecision_command.hpp"
#include "cases/case_set.hpp"
#include "solvers/solver.hpp"
#include "sweep/processes.hpp"

namespace {

constexpr int kRuntimeFailure = 1;
constexpr int kBadInput = 2;

// A message echoes what the user wrote (a key, a value, a file name), and not every
// source clips it (pb::clip): each ": "-separated part, and then the line, is bounded here
// so that the field and the reason survive a 10 MB key.
constexpr std::size_t kMaxMessagePart = 200;
constexpr std::size_t kMaxMessage = 1000;

std::string bounded(const std::string& message) {
  std::string line;
  for (std::size_t start = 0; start <= message.size();) {
    const std::size_t end = std::min(message.find(": ", start), message.size());
    if (start > 0) line += ": ";
    line += pb::clip(std::string_view(message).substr(start, end - start), kMaxMessagePart);
    start = end + 2;
  }
  return pb::clip(line, kMaxMessage);
}

int fail(const std::string& message, int code) {
  std::string line = bounded(message);
  std::replace(line.begin(), line.end(), '\n', ' ');  // one line, whatever the source
  std::cerr << "poundbench: " << line << '\n';
  return code;
}

// CLI11 reads an empty word as 0, or leaves the default, for a number (`--pi3 ''` ran
// with Pi3 = 0), and no option of poundbench means anything by an empty value: every
// option that takes a value, of every subcommand, refuses it.
void refuse_empty_values(CLI::App& app) {
  static const CLI::Validator kNotEmpty(
      [](std::string& value) { return value.empty() ? std::string("empty value (give one)") : std::string(); }, "",
      "NOT_EMPTY");
  for (CLI::Option* option : app.get_options())
    if (option->get_type_size() > 0) option->check(kNotEmpty);
  for (CLI::App* sub : app.get_subcommands({})) refuse_empty_values(*sub);
}

int list_solvers() {
  std::size_t width = 0;
  for (const pb::SolverInfo& s : pb::solvers()) width = std::max(width, s.name.size());
  for (const pb::SolverInfo& s : pb::solvers())
    std::cout << s.name << std::string(width + 2 - s.name.size(), ' ') << s.summary << '\n';
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::unique_ptr<pb::Processes> processes;
  try {
    processes = std::make_unique<pb::Processes>(argc, argv);
  } catch (const std::exception& e) {
    return fail(e.what(), kRuntimeFailure);
  }
  const bool leader = processes->leader();

  CLI::App app{"poundbench: time-stepping solvers with impacts on the pounding case set"};
  app.require_subcommand(1);
  pb::app::RunFlags run_flags;
  pb::app::SpectrumFlags spectrum_flags;
  CLI::App* run = pb::app::add_run_command(app, run_flags);
  CLI::App* spectrum = pb::app::add_spectrum_command(app, spectrum_flags);
  pb::app::WorkPrecisionFlags workprecision_flags;
  CLI::App* workprecision = pb::app::add_workprecision_command(app, workprecision_flags);
  pb::app::StressFlags stress_flags;
  CLI::App* stress = pb::app::add_stress_command(app, stress_flags);
  pb::app::BaselineFlags baseline_flags;
  CLI::App* baseline = pb::app::add_baseline_command(app, baseline_flags);
  pb::app::CompareFlags compare_flags;
  CLI::App* compare = pb::app::add_compare_command(app, compare_flags);
  CLI::App* solvers = app.add_subcommand("solvers", "List the solvers and what each one is");
  refuse_empty_values(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Every rank parses the same words, so every rank ends here alike.
    if (e.get_exit_code() == 0) return leader ? app.exit(e) : 0;  // --help
    return leader ? fail(e.what(), kBadInput) : kBadInput;
  }

  // A failure of this process alone: the other ranks of a job must not wait for it.
  const auto local_failure = [&](const char* message, int code) {
    fail(message, code);
    processes->abort_others(code);
    return code;
  };
  try {
    if (*spectrum) return pb::app::spectrum_command(*spectrum, spectrum_flags, *processes);
    if (*workprecision) return pb::app::workprecision_command(*workprecision, workprecision_flags, *processes);
    if (*stress) return pb::app::stress_command(*stress, stress_flags, *processes);
    // The other commands are not shared out: the leader alone runs them.
    if (!leader) return 0;
    if (*run) return pb::app::run_command(*run, run_flags);
    if (*baseline) return pb::app::baseline_command(*baseline, baseline_flags);
    if (*compare) return pb::app::compare_command(*compare, compare_flags);
    if (*solvers) return list_solvers();
  } catch (const pb::SharedFailure& e) {
    return leader ? fail(e.what(), e.code) : e.code;
  } catch (const std::exception& e) {
    return local_failure(e.what(), pb::app::exit_code_of(e));
  }
  return kBadInput;
}
