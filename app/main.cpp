// poundbench: the command line. Exit codes: 0 done, 1 runtime failure, 2 bad input (one
// line on stderr naming the flag or file, the field and the reason), 130 interrupted.
// Under an MPI launcher every rank runs this; only the leader (rank 0) prints, and the
// sweep commands share their work among the ranks (sweep/processes.hpp).

#include <algorithm>
#include <exception>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/adapter_command.hpp"
#include "app/baseline_command.hpp"
#include "app/blas_threads.hpp"
#include "app/report_command.hpp"
#include "app/run_command.hpp"
#include "app/solvers_command.hpp"
#include "app/spectrum_command.hpp"
#include "app/separation_command.hpp"
#include "app/stress_command.hpp"
#include "app/version.hpp"
#include "app/workprecision_command.hpp"
#include "cases/case_set.hpp"
#include "cases/nearest_name.hpp"
#include "cases/text.hpp"
#include "frontend/errors.hpp"
#include "sweep/processes.hpp"

namespace {

constexpr int kRuntimeFailure = 1;
constexpr int kBadInput = 2;

int fail(const std::string& message, int code) {
  std::cerr << "poundbench: " << pb::app::one_line(message) << '\n';
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

// "the subcommands are: run, ..., solvers (...)", for the lines that refuse a command line
// for its subcommand.
std::string subcommand_list(const CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands(nullptr)) names += (names.empty() ? "" : ", ") + sub->get_name();
  return "the subcommands are: " + names + " (`poundbench help` says what each does)";
}

const CLI::App* find_subcommand(const CLI::App& app, std::string_view name) {
  for (const CLI::App* sub : app.get_subcommands(nullptr))
    if (sub->get_name() == name) return sub;
  return nullptr;
}

// The first word that is not an option names the subcommand (the top level's options,
// --help and --version, take no value). CLI11 would answer a word that is not one with
// "A subcommand is required"; this names the word and lists them. `help [SUBCOMMAND]` is
// read as --help. Returns the exit code when the command line ends here.
std::optional<int> check_subcommand_word(const CLI::App& app, int argc, char** argv, bool leader) {
  const auto unknown = [&](std::string_view word) {
    std::vector<std::string_view> names;
    for (const CLI::App* sub : app.get_subcommands(nullptr)) names.push_back(sub->get_name());
    const std::string_view best = pb::nearest_name(word, names);
    const std::string line = "unknown subcommand '" + pb::clip(word) + "'" +
                             (best.empty() ? "" : " (did you mean " + std::string(best) + "?)") + "; " +
                             subcommand_list(app);
    return leader ? fail(line, kBadInput) : kBadInput;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string_view word = argv[i];
    if (word.starts_with('-')) continue;
    if (word != "help") return find_subcommand(app, word) ? std::nullopt : std::optional<int>(unknown(word));
    if (i + 1 == argc) {
      if (leader) std::cout << app.help();
      return 0;
    }
    const CLI::App* about = find_subcommand(app, argv[i + 1]);
    if (!about) return unknown(argv[i + 1]);
    if (leader) std::cout << about->help(app.get_name());
    return 0;
  }
  return std::nullopt;
}

// CLI11's "The following argument was not expected: --treads" as poundbench words it, with
// the nearest flag of the subcommand when the word is a typo of one (as a case-set key's
// is: cases/nearest_name.hpp): "spectrum: unknown flag --treads (did you mean --threads?)".
// The unknown words are found in argv, not in CLI11's text: a word that starts with "--"
// and is a flag neither of the subcommand nor of the top level.
std::string flag_error(const CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  if (!dynamic_cast<const CLI::ExtrasError*>(&e)) return e.what();
  const CLI::App* sub = nullptr;
  for (int i = 1; i < argc && !sub; ++i)
    if (!std::string_view(argv[i]).starts_with('-')) sub = find_subcommand(app, argv[i]);
  std::vector<std::string> flags;
  for (const CLI::App* scope : {&app, sub})
    if (scope)
      for (const CLI::Option* option : scope->get_options())
        for (const std::string& name : option->get_lnames()) flags.push_back("--" + name);
  const std::vector<std::string_view> names(flags.begin(), flags.end());
  std::string line;
  for (int i = 1; i < argc; ++i) {
    const std::string_view word(argv[i]);
    if (word == "--") break;  // what follows is not flags
    if (!word.starts_with("--")) continue;
    const std::string_view flag = word.substr(0, word.find('='));
    if (std::find(names.begin(), names.end(), flag) != names.end()) continue;
    const std::string_view best = pb::nearest_name(flag, names);
    line += (line.empty() ? "" : "; ") + std::string("unknown flag ") + pb::clip(flag) +
            (best.empty() ? "" : " (did you mean " + std::string(best) + "?)");
  }
  if (line.empty()) return e.what();
  if (!sub) return line + "; `poundbench help` lists the subcommands";
  return sub->get_name() + ": " + line + "; `poundbench help " + sub->get_name() + "` lists its flags";
}

// A subcommand and the flags its options write into (so neither is copied or moved).
template <class Flags>
struct Command {
  Flags flags;
  CLI::App* app;
  Command(CLI::App& parent, CLI::App* (*add)(CLI::App&, Flags&)) : app(add(parent, flags)) {}
  Command(const Command&) = delete;
  Command& operator=(const Command&) = delete;
};

}  // namespace

int main(int argc, char** argv) {
  pb::app::stop_blas_threads();
  std::unique_ptr<pb::Processes> processes;
  try {
    processes = std::make_unique<pb::Processes>(argc, argv);
  } catch (const std::exception& e) {
    return fail(e.what(), kRuntimeFailure);
  }
  const bool leader = processes->leader();

  CLI::App app{"poundbench: time-stepping solvers with impacts on the pounding case set", "poundbench"};
  app.require_subcommand(0, 1);  // none: the message below lists them
  app.set_version_flag("--version", std::string("poundbench ") + pb::app::kVersion + ", commit " + pb::app::kCommit,
                       "Print the version and the commit it was built from");
  app.footer("`poundbench help SUBCOMMAND` is `poundbench SUBCOMMAND --help`.");
  Command run(app, &pb::app::add_run_command);
  Command spectrum(app, &pb::app::add_spectrum_command);
  Command workprecision(app, &pb::app::add_workprecision_command);
  Command stress(app, &pb::app::add_stress_command);
  Command separation(app, &pb::app::add_separation_command);
  Command baseline(app, &pb::app::add_baseline_command);
  Command compare(app, &pb::app::add_compare_command);
  Command solvers(app, &pb::app::add_solvers_command);
  Command adapter(app, &pb::app::add_adapter_command);
  Command report(app, &pb::app::add_report_command);
  refuse_empty_values(app);

  // Every rank parses the same words, so every rank ends here alike.
  if (const std::optional<int> code = check_subcommand_word(app, argc, argv, leader)) return *code;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return leader ? app.exit(e) : 0;  // --help, --version
    return leader ? fail(flag_error(app, e, argc, argv), kBadInput) : kBadInput;
  }
  if (app.get_subcommands().empty()) {
    const std::string line = "no subcommand; " + subcommand_list(app);
    return leader ? fail(line, kBadInput) : kBadInput;
  }

  // A failure of this process alone: the other ranks of a job must not wait for it.
  const auto local_failure = [&](const char* message, int code) {
    fail(message, code);
    processes->abort_others(code);
    return code;
  };
  try {
    if (*spectrum.app) return pb::app::spectrum_command(*spectrum.app, spectrum.flags, *processes);
    if (*workprecision.app)
      return pb::app::workprecision_command(*workprecision.app, workprecision.flags, *processes);
    if (*stress.app) return pb::app::stress_command(*stress.app, stress.flags, *processes);
    // The other commands are not shared out: the leader alone runs them.
    if (!leader) return 0;
    if (*run.app) return pb::app::run_command(*run.app, run.flags);
    if (*baseline.app) return pb::app::baseline_command(*baseline.app, baseline.flags);
    if (*separation.app) return pb::app::separation_command(separation.flags);
    if (*compare.app) return pb::app::compare_command(*compare.app, compare.flags);
    if (*solvers.app) return pb::app::solvers_command(solvers.flags);
    if (*adapter.app) return pb::app::adapter_command(*adapter.app, adapter.flags);
    if (*report.app) return pb::app::report_command(report.flags);
  } catch (const pb::SharedFailure& e) {
    return leader ? fail(e.what(), e.code) : e.code;
  } catch (const std::exception& e) {
    return local_failure(e.what(), pb::app::exit_code_of(e));
  }
  return kBadInput;
}
