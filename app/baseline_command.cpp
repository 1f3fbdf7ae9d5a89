#include "app/baseline_command.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "app/errors.hpp"
#include "app/output_files.hpp"
#include "app/study_run.hpp"
#include "app/sweep_watch.hpp"
#include "cases/case_set.hpp"
#include "studies/baseline.hpp"
#include "rows/minimal_rows.hpp"
#include "rows/row_read.hpp"

extern char** environ;

namespace pb::app {

namespace fs = std::filesystem;

namespace {

constexpr int kCheckFailed = 1;

// The first line a program prints, or "unknown". The program runs from an argument vector,
// never through a shell: its arguments hold paths the user chose, which a shell would
// read as commands. stdin and stderr are /dev/null.
std::string first_line_of(std::vector<std::string> args) {
  int out[2];
  if (::pipe2(out, O_CLOEXEC) != 0) return "unknown";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = ::posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out[1]);
  std::string text;
  if (spawned == 0) {
    char buffer[256];
    ssize_t n = 0;
    // Read to the end, so the program never blocks on a full pipe.
    while ((n = ::read(out[0], buffer, sizeof buffer)) > 0 || (n < 0 && errno == EINTR))
      if (n > 0 && text.size() < 4096) text.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(out[0]);
  int status = 0;
  if (spawned != 0 || ::waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return "unknown";
  std::string line = text.substr(0, text.find('\n'));
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line.empty() ? "unknown" : line;
}

// Provenance for people: the commit of the tree the baseline sits in, the compiler, the date.
std::vector<std::string> provenance(const fs::path& file) {
  const std::string dir = fs::absolute(file).parent_path().string();
  std::string commit = first_line_of({"git", "-C", dir, "rev-parse", "--short", "HEAD"});
  if (commit != "unknown" &&
      first_line_of({"git", "-C", dir, "status", "--porcelain", "--untracked-files=no"}) != "unknown")
    commit += " (with uncommitted changes)";
  char date[32] = {};
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  #if defined(__clang__)
  const std::string compiler = std::string("clang ") + __clang_version__;
#else
  const std::string compiler = std::string("GCC ") + __VERSION__;
#endif
  return {"commit: " + commit, "compiler: " + compiler, std::string("made: ") + date};
}

fs::path relative_to_file(const fs::path& target, const fs::path& file) {
  return fs::relative(fs::absolute(target), fs::absolute(file).parent_path());
}

struct Source {
  CaseSet set;
  std::optional<SettingsList> list;
};

Source load_source(const fs::path& cases, const fs::path& settings) {
  Source s{load_case_set(cases), std::nullopt};  // CaseSetError: bad input
  if (s.set.cases.empty()) throw BadInput(cases.string() + ": no cases");
  if (!settings.empty()) s.list = read_settings_list(settings.string(), true);
  return s;
}

// Runs a baseline's sweeps, showing progress; nullopt when interrupted.
std::optional<std::vector<Row>> run(const Source& s, unsigned threads) {
  const std::size_t total = s.set.cases.size() * ((s.list ? s.list->runs.size() : 0) + 1);
  SweepWatch watch("baseline", "runs", total, 0, progress_on_stderr(true), [] { std::_Exit(kInterrupted); });
  SweepOptions options;
  options.threads = threads;
  options.cancel = &watch.cancel();
  options.on_progress = [&](std::size_t done, std::size_t) { watch.set_done(done); };
  std::vector<Row> rows = run_baseline(s.set.cases, s.list ? &*s.list : nullptr, options);
  watch.finish();
  if (watch.interrupted() || rows.empty()) return std::nullopt;
  return rows;
}

void store(const fs::path& file, const BaselineHeader& header, const std::vector<Row>& rows) {
  write_atomically(file, [&](std::ostream& out) {
    for (const std::string& line : header_lines(header)) out << '#' << line << '\n';
    write_csv(out, rows);
  });
  report_written(rows.size(), file.string());
}

RowFile read_rows(const std::string& path) {
  try {
    return read_csv_file(path);
  } catch (const RowReadError& e) {
    throw BadInput(e.what());
  }
}

int interrupted() {
  std::fprintf(stderr, "poundbench: interrupted; nothing was written\n");
  return kInterrupted;
}

}  // namespace

CLI::App* add_baseline_command(CLI::App& app, BaselineFlags& flags) {
  CLI::App* command = app.add_subcommand(
      "baseline", "Store, check or update accuracy regression baselines (rows of a case set per solver setting)");
  command->add_option("CASESET", flags.case_set, "Case-set file to store a new baseline of");
  command->add_option("--settings", flags.settings, "Settings list whose runs the baseline also stores");
  command->add_option("--out", flags.out, "The new baseline file (CSV)");
  command->add_option("--check", flags.check, "Rerun these baselines and compare (exit 1 on a change)");
  command->add_option("--update", flags.update, "Rerun these baselines and store them again");
  command->add_option("--threads", flags.threads, "Worker threads (default: all cores)");
  return command;
}

int baseline_command(const CLI::App& command, const BaselineFlags& flags) {
  const int modes = (flags.case_set.empty() ? 0 : 1) + (flags.check.empty() ? 0 : 1) + (flags.update.empty() ? 0 : 1);
  if (modes != 1) throw BadInput("baseline: give one of CASESET (with --out), --check FILE... or --update FILE...");
  if (command.count("--threads") && flags.threads == 0) throw BadInput("--threads: must be >= 1");

  if (!flags.case_set.empty()) {
    if (flags.out.empty()) throw BadInput("--out: required with CASESET");
    check_output_target(flags.out, "--out");
    const Source s = load_source(flags.case_set, flags.settings);
    std::vector<NamedFile> inputs = record_files(s.set.cases);
    inputs.push_back({"CASESET", flags.case_set});
    if (!flags.settings.empty()) inputs.push_back({"--settings", flags.settings});
    check_outputs_apart({{"--out", flags.out}}, inputs);
    const std::optional<std::vector<Row>> rows = run(s, flags.threads);
    if (!rows) return interrupted();
    BaselineHeader header{relative_to_file(flags.case_set, flags.out).string(),
                          flags.settings.empty() ? "" : relative_to_file(flags.settings, flags.out).string(),
                          provenance(flags.out)};
    store(flags.out, header, *rows);
    return 0;
  }

  const bool update = !flags.update.empty();
  bool all_passed = true;
  for (const std::string& file : update ? flags.update : flags.check) {
    const RowFile stored = read_rows(file);
    BaselineHeader header;
    try {
      header = parse_header(stored.comments, file);
    } catch (const RowReadError& e) {
      throw BadInput(e.what());
    }
    const fs::path dir = fs::absolute(file).parent_path();
    const Source s = load_source(dir / header.cases, header.settings.empty() ? fs::path() : dir / header.settings);
    const std::optional<std::vector<Row>> rows = run(s, flags.threads);
    if (!rows) return interrupted();
    const std::vector<Comparison> table = compare_rows(*rows, stored.rows, Match::same_setting);
    std::cout << file << ":\n" << comparison_table(table, Match::same_setting);
    bool passed = true;
    for (const Comparison& c : table) passed = passed && c.passed(Match::same_setting);
    if (update) {
      header.notes = provenance(file);
      store(file, header, *rows);
      std::cout << file << ": stored again (" << rows->size() << " rows)" << (passed ? "" : "; it had changed")
                << '\n';
    }
    all_passed = all_passed && passed;
  }
  return all_passed || update ? 0 : kCheckFailed;
}

CLI::App* add_compare_command(CLI::App& app, CompareFlags& flags) {
  CLI::App* command = app.add_subcommand(
      "compare", "Compare result rows (another program's, or spectrum's) with a baseline's rows of the same cases");
  std::string columns;
  for (std::string_view column : minimal_columns()) columns += (columns.empty() ? "" : ", ") + std::string(column);
  command
      ->add_option("ROWS", flags.rows,
                   "CSV rows to check, with a header naming at least the columns " + columns +
                       " (of pi5 to bodies, those the row's scene uses); any other column of `poundbench spectrum` "
                       "may be there (docs/cli.md)")
      ->required();
  command->add_option("--baseline", flags.baseline, "Baseline file (tests/baselines/)")->required();
  command->add_option("--tolerance", flags.tolerance, "Largest relative Pi1 difference let through");
  command->add_flag("--same-setting", flags.same_setting,
                    "Compare with the stored rows of each row's own solver setting (its stated tolerance)");
  return command;
}

int compare_command(const CLI::App& command, const CompareFlags& flags) {
  const bool given = command.count("--tolerance") > 0;
  if (!flags.same_setting && !given) throw BadInput("--tolerance: required (or --same-setting)");
  if (given && !(flags.tolerance >= 0.0 && std::isfinite(flags.tolerance)))
    throw BadInput("--tolerance: must be finite and >= 0");
  RowFile rows;
  try {
    rows = read_minimal_csv_file(flags.rows);
  } catch (const RowReadError& e) {
    throw BadInput(e.what());
  }
  const RowFile stored = read_rows(flags.baseline);
  if (rows.rows.empty()) throw BadInput(flags.rows + ": no rows");
  const Match match = flags.same_setting ? Match::same_setting : Match::reference;
  const std::vector<Comparison> table =
      compare_rows(rows.rows, stored.rows, match, given ? flags.tolerance : std::numeric_limits<double>::quiet_NaN());
  std::cout << comparison_table(table, match);
  bool passed = true;
  for (const Comparison& c : table) passed = passed && c.passed(match);
  return passed ? 0 : kCheckFailed;
}

}  // namespace pb::app
