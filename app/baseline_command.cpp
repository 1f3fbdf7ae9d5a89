#include "app/baseline_command.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "app/check_report.hpp"
#include "output/output_files.hpp"
#include "app/study_run.hpp"
#include "output/sweep_watch.hpp"
#include "app/version.hpp"
#include "cases/case_set.hpp"
#include "frontend/errors.hpp"
#include "rows/minimal_rows.hpp"
#include "rows/row_read.hpp"
#include "studies/baseline.hpp"

namespace pb::app {

namespace fs = std::filesystem;

namespace {

constexpr int kCheckFailed = 1;

// Provenance for people: the commit of the poundbench that made the rows (its build's, as
// `poundbench --version` says it: the rows are this binary's, whatever tree the file sits
// in), the compiler, the date.
std::vector<std::string> provenance() {
  char date[32] = {};
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
#if defined(__clang__)
  const std::string compiler = std::string("clang ") + __clang_version__;
#else
  const std::string compiler = std::string("GCC ") + __VERSION__;
#endif
  return {std::string("commit: ") + kCommit + " (poundbench " + kVersion + ")", "compiler: " + compiler,
          std::string("made: ") + date};
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

// A comparison line as a JUnit testcase names it: family and setting.
std::string label_of(const Comparison& c) { return (c.family.empty() ? "-" : c.family) + " " + setting_text(c); }

// Why a comparison line failed, one line for a JUnit failure ("" when it passed).
std::string failure_of(const Comparison& c, Match match, bool allow_unmatched) {
  if (c.passed(match, allow_unmatched)) return {};
  std::ostringstream why;
  if (c.failed > 0)
    why << c.failed << " of " << c.compared << " compared rows beyond " << c.tolerance << " (largest relative |dPi1| "
        << c.max_difference << " at point " << c.worst_point << ")";
  if (c.compared == 0) why << "no row matched a stored case";
  if (c.unmatched > 0 && !allow_unmatched) {
    why << (why.tellp() > 0 ? "; " : "") << c.unmatched << " unmatched rows";
    if (!c.unmatched_rows.empty())
      why << " (point " << c.unmatched_rows[0].point << ": " << c.unmatched_rows[0].nearest << ")";
  }
  if (match == Match::same_setting && c.missing > 0)
    why << (why.tellp() > 0 ? "; " : "") << c.missing << " stored rows with no row";
  return why.str();
}

int interrupted() {
  std::fprintf(stderr, "poundbench: interrupted; nothing was written\n");
  return kInterrupted;
}

// A stored baseline file as `baseline --check` and `--update` read it, with the case set
// (and settings list) its header names.
struct StoredBaseline {
  std::string file;
  RowFile stored;
  BaselineHeader header;
  Source source;
};

StoredBaseline load_stored(const std::string& file) {
  RowFile stored = read_rows(file);
  BaselineHeader header;
  try {
    header = parse_header(stored.comments, file);
  } catch (const RowReadError& e) {
    throw BadInput(e.what());
  }
  const fs::path dir = fs::absolute(file).parent_path();
  Source s = load_source(dir / header.cases, header.settings.empty() ? fs::path() : dir / header.settings);
  return {file, std::move(stored), std::move(header), std::move(s)};
}

// --junit of `baseline --check` is written after every file is checked: refused before the
// first run when it is one of a baseline's inputs (the file, its case set, settings, records).
void check_junit_apart(const std::string& junit, const StoredBaseline& b) {
  if (junit.empty()) return;
  const fs::path dir = fs::absolute(b.file).parent_path();
  std::vector<NamedFile> inputs = record_files(b.source.set.cases);
  inputs.push_back({"--check", b.file});
  inputs.push_back({"the baseline's case set", dir / b.header.cases});
  if (!b.header.settings.empty()) inputs.push_back({"the baseline's settings", dir / b.header.settings});
  check_outputs_apart({{"--junit", junit}}, inputs);
}

// --check or --update of every file given. Each file, its case set and settings are read
// (and --junit checked against them all) before the first run, so that a bad file or an
// overlap is refused at once and not after the runs of the files before it.
int check_or_update(const BaselineFlags& flags) {
  const bool update = !flags.update.empty();
  std::vector<StoredBaseline> baselines;
  for (const std::string& file : update ? flags.update : flags.check) {
    baselines.push_back(load_stored(file));
    check_junit_apart(flags.junit, baselines.back());
  }
  bool all_passed = true;
  std::vector<Verdict> verdicts;
  for (StoredBaseline& b : baselines) {
    const std::optional<std::vector<Row>> rows = run(b.source, flags.threads);
    if (!rows) return interrupted();
    const std::vector<Comparison> table = compare_rows(*rows, b.stored.rows, Match::same_setting);
    std::cout << b.file << ":\n" << comparison_table(table, Match::same_setting);
    bool passed = true;
    for (const Comparison& c : table) {
      passed = passed && c.passed(Match::same_setting);
      verdicts.push_back({b.file, label_of(c), failure_of(c, Match::same_setting, false)});
    }
    if (update) {
      b.header.notes = provenance();
      store(b.file, b.header, *rows);
      std::cout << b.file << ": stored again (" << rows->size() << " rows)" << (passed ? "" : "; it had changed")
                << '\n';
    }
    all_passed = all_passed && passed;
  }
  write_junit(flags.junit, "baseline --check", verdicts);
  return all_passed || update ? 0 : kCheckFailed;
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
  add_junit_flag(*command, flags.junit, "family and setting of each file");
  return command;
}

int baseline_command(const CLI::App& command, const BaselineFlags& flags) {
  const int modes = (flags.case_set.empty() ? 0 : 1) + (flags.check.empty() ? 0 : 1) + (flags.update.empty() ? 0 : 1);
  if (modes != 1) throw BadInput("baseline: give one of CASESET (with --out), --check FILE... or --update FILE...");
  if (command.count("--threads") && flags.threads == 0) throw BadInput("--threads: must be >= 1");
  check_junit_target(flags.junit, !flags.check.empty());

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
                          provenance()};
    store(flags.out, header, *rows);
    return 0;
  }

  return check_or_update(flags);
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
  command->add_flag("--allow-unmatched", flags.allow_unmatched,
                    "Pass a family whose rows matched no stored case (within 1e-5 on every number of the case) "
                    "when its other rows pass; by default such a row fails it");
  add_junit_flag(*command, flags.junit, "family and setting");
  return command;
}

int compare_command(const CLI::App& command, const CompareFlags& flags) {
  const bool given = command.count("--tolerance") > 0;
  if (!flags.same_setting && !given) throw BadInput("--tolerance: required (or --same-setting)");
  if (given && !(flags.tolerance >= 0.0 && std::isfinite(flags.tolerance)))
    throw BadInput("--tolerance: must be finite and >= 0");
  check_junit_target(flags.junit, true);
  check_outputs_apart({{"--junit", flags.junit}}, {{"ROWS", flags.rows}, {"--baseline", flags.baseline}});
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
  std::cout << comparison_table(table, match, flags.allow_unmatched);
  bool passed = true;
  std::vector<Verdict> verdicts;
  for (const Comparison& c : table) {
    passed = passed && c.passed(match, flags.allow_unmatched);
    verdicts.push_back({"compare " + flags.rows, label_of(c), failure_of(c, match, flags.allow_unmatched)});
  }
  write_junit(flags.junit, "compare", verdicts);
  return passed ? 0 : kCheckFailed;
}

}  // namespace pb::app
