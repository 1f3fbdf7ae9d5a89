// The fuzz harness of issue 15 as tests: every corpus file replayed (one test each, named
// after the file), then a short seeded mutation campaign per target. The campaigns are
// deterministic (seed 15 unless POUNDBENCH_FUZZ_SEED says otherwise); scripts/fuzz.sh runs
// them longer through the environment variables that Budget reads (harness.cpp).

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <chrono>
#include <fstream>
#include <optional>
#include <set>

#include "tests/fuzz/callables.hpp"
#include "tests/fuzz/harness.hpp"
#include "tests/fuzz/mutator.hpp"
#include "tests/fuzz/physical_target.hpp"
#include "tests/fuzz/persistent.hpp"
#include "tests/fuzz/report_target.hpp"
#include "tests/fuzz/targets.hpp"

namespace pb::fuzz {
namespace {

const Budget& budget() {
  static const Budget b = Budget::from_build_and_environment();
  return b;
}

std::string test_name(const fs::path& file) {
  std::string name = file.stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

// ---- The corpus: the inputs issue 15 lists, and whatever campaigns found since. ----

class ReaderCorpus : public ::testing::TestWithParam<fs::path> {};
class CliCorpus : public ::testing::TestWithParam<fs::path> {};

TEST_P(ReaderCorpus, ReadsOrRefusesInOneLine) {
  const fs::path& file = GetParam();
  const Reader reader = file.parent_path().filename() == "case_set" ? Reader::case_set : Reader::settings;
  // Generators (@REPEAT@, @SEQ@) stand for inputs too big to store, such as a 10^7-character key.
  const std::string text = expand_generators(read_file(file));
  if (auto problem = check_reader(reader, text, budget().reader_limits)) ADD_FAILURE() << file << ": " << *problem;
}

TEST_P(CliCorpus, ExitsZeroOrTwoInTimeWithOneLine) {
  const fs::path& file = GetParam();
  const std::vector<std::string> args = read_args_file(file);
  if (auto problem = check_cli(args, budget().cli_limits))
    ADD_FAILURE() << file << ": " << *problem << "\n  arguments: " << excerpt(args_text(args), 400);
}

std::vector<fs::path> reader_corpus() {
  std::vector<fs::path> files = corpus_files("case_set");
  for (const fs::path& f : corpus_files("settings")) files.push_back(f);
  return files;
}

// Test names: the corpus file's name (its folder too for the readers).
std::string reader_test_name(const ::testing::TestParamInfo<fs::path>& p) {
  return p.param.parent_path().filename().string() + "_" + test_name(p.param);
}
std::string cli_test_name(const ::testing::TestParamInfo<fs::path>& p) { return test_name(p.param); }

INSTANTIATE_TEST_SUITE_P(Fuzz, ReaderCorpus, ::testing::ValuesIn(reader_corpus()), reader_test_name);
INSTANTIATE_TEST_SUITE_P(Fuzz, CliCorpus, ::testing::ValuesIn(corpus_files("cli")), cli_test_name);

// Issue 33's targets (targets.hpp): records, answers, case documents, Python keywords.
class DocumentCorpus : public ::testing::TestWithParam<fs::path> {};

TEST_P(DocumentCorpus, IsReadOrRefusedInOneLineAndNeverCrashes) {
  const fs::path& file = GetParam();
  const std::string folder = file.parent_path().filename().string();
  const std::string text = expand_generators(read_file(file));
  std::optional<std::string> problem;
  if (folder == "python") {
    if (!python_available()) GTEST_SKIP() << "the Python module is not built";
    // A first line starting with '#' says what the entry found; the rest is the keywords.
    problem = check_python(text.starts_with('#') ? text.substr(text.find('\n') + 1) : text, budget().cli_limits);
  } else {
    const Document kind = folder == "record" ? Document::record
                          : folder == "answer" ? Document::answer
                                               : Document::case_document;
    problem = check_document(kind, text, budget().cli_limits, true);
  }
  if (problem) ADD_FAILURE() << file << ": " << *problem;
}

std::vector<fs::path> document_corpus() {
  std::vector<fs::path> files;
  for (const char* folder : {"record", "answer", "document", "python"})
    for (const fs::path& f : corpus_files(folder)) files.push_back(f);
  return files;
}

INSTANTIATE_TEST_SUITE_P(Fuzz, DocumentCorpus, ::testing::ValuesIn(document_corpus()), reader_test_name);

// ---- Seeded mutation campaigns. ----

struct Finding {
  std::uint64_t index;
  std::string problem;
  fs::path saved;
};

// A finding's kind: its text up to the first value, without numbers or repeated letters
// ("message is 88132 characters (> 300): fuzz.toml:5: kkkk..." and the same at 9644 are one).
std::string signature(const std::string& problem) {
  std::string kind;
  for (char c : problem.substr(0, problem.find("; stdout")).substr(0, 80)) {
    if (std::isdigit(static_cast<unsigned char>(c))) continue;
    if (!kind.empty() && kind.back() == c) continue;
    kind += c;
  }
  return kind.substr(0, 36);
}

// Runs inputs 0, 1, ... of `target` (or the one POUNDBENCH_FUZZ_INDEX names) until the
// count or the time is spent, or max_failures inputs failed. `make` builds input i from
// its own Rng; `check` returns the violated property; `save` writes a failing input.
template <class Make, class Check>
std::vector<Finding> campaign(const std::string& target, std::size_t count, const std::string& extension, Make make,
                              Check check) {
  const Budget& b = budget();
  const auto start = std::chrono::steady_clock::now();
  std::vector<Finding> findings;
  std::set<std::string> kinds;
  std::size_t done = 0, repeats = 0;
  for (std::uint64_t index = b.only_index.value_or(0);; ++index) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (b.only_index ? done == 1 : b.seconds > 0 ? elapsed >= b.seconds : done >= count) break;
    ++done;
    Rng rng(input_seed(b.seed, target, index));
    const auto input = make(rng);
    auto problem = check(input);
    if (!problem) continue;
    // One report per kind of finding: a campaign would otherwise fill its quota with the
    // commonest bug (a huge key echoed in full) and hide the rest.
    const std::string kind = signature(*problem);
    if (!kinds.insert(kind).second) {
      ++repeats;
      continue;
    }
    Finding f{index, *problem, {}};
    if (!b.failures_dir.empty()) {
      fs::create_directories(b.failures_dir);
      f.saved = b.failures_dir / (target + "-seed" + std::to_string(b.seed) + "-" + std::to_string(index) + extension);
      std::ofstream(f.saved, std::ios::binary) << input;
    }
    findings.push_back(std::move(f));
    if (findings.size() >= b.max_failures) break;
  }
  std::printf("%s: %zu inputs, seed %llu, %zu findings (and %zu more of the same kinds), %.1f s\n",
              target.c_str(), done, static_cast<unsigned long long>(b.seed), findings.size(), repeats,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return findings;
}

void report(const std::vector<Finding>& findings, const std::string& gtest_filter) {
  for (const Finding& f : findings)
    ADD_FAILURE() << "input " << f.index << ": " << f.problem << "\n  reproduce: POUNDBENCH_FUZZ_SEED="
                  << budget().seed << " POUNDBENCH_FUZZ_INDEX=" << f.index << " POUNDBENCH_FUZZ_FAILURES=fuzz-failures "
                  << fs::read_symlink("/proc/self/exe").string() << " --gtest_filter=" << gtest_filter
                  << (f.saved.empty() ? "" : "\n  saved: " + f.saved.string());
}

void reader_campaign(Reader reader, const std::string& target, const std::string& filter) {
  const std::vector<std::string> seeds = reader_seeds(reader);
  report(campaign(
             target, budget().reader_inputs, ".toml",
             [&](Rng& rng) { return mutate_toml(rng.pick(seeds), seeds, rng); },
             [&](const std::string& text) { return check_reader(reader, text, budget().reader_limits); }),
         filter);
}

TEST(CaseSetReaderFuzz, ReturnsCasesOrOneLineError) {
  reader_campaign(Reader::case_set, "case_set", "CaseSetReaderFuzz.*");
}

TEST(SettingsReaderFuzz, ReturnsRunsOrOneLineError) {
  reader_campaign(Reader::settings, "settings", "SettingsReaderFuzz.*");
}

TEST(CliFuzz, ExitsZeroOrTwoInTimeWithOneLineAndNoStrayFile) {
  const std::vector<std::vector<std::string>> seeds = cli_seeds();
  const auto make = [&](Rng& rng) {
    std::vector<std::string> args = rng.pick(seeds);
    // A time limit of our own, never mutated, on the commands that take one: then a run
    // that outlives the harness's timeout ignored it, which is a hang and not a slow case.
    if (args[0] == "run" || args[0] == "spectrum") args.insert(args.end(), {"--time-limit", "2"});
    return args_text(mutate_args(args, {"--time-limit"}, rng));
  };
  report(campaign(
             "cli", budget().cli_runs, ".args", make,
             [&](const std::string& text) {
               // The arguments travel as the text of an .args file, the form the corpus keeps.
               const fs::path tmp = fs::temp_directory_path() / ("poundbench-fuzz-args-" + std::to_string(::getpid()));
               std::ofstream(tmp, std::ios::binary) << text;
               const std::vector<std::string> args = read_args_file(tmp);
               fs::remove(tmp);
               auto problem = check_cli(args, budget().cli_limits);
               if (problem) *problem += "\n  arguments: " + excerpt(text, 400);
               return problem;
             }),
         "CliFuzz.*");
}

void document_campaign(Document kind, const std::string& target, const std::string& filter, std::size_t count) {
  const std::vector<std::string> seeds = document_seeds(kind);
  report(campaign(
             target, count, kind == Document::record ? ".at2" : ".json",
             [&](Rng& rng) { return mutate_document(kind, rng.pick(seeds), seeds, rng); },
             [&](const std::string& text) { return check_document(kind, text, budget().reader_limits); }),
         filter);
}

TEST(RecordReaderFuzz, ReturnsARecordOrOneLineError) {
  document_campaign(Document::record, "record", "RecordReaderFuzz.*", budget().reader_inputs);
}

TEST(AnswerReaderFuzz, AcceptsOnlyAnswersWithAPi1FromTheRun) {
  document_campaign(Document::answer, "answer", "AnswerReaderFuzz.*", budget().reader_inputs);
}

// Each accepted document is solved by an engine: half the count of the readers' campaigns.
TEST(AdapterDocumentFuzz, RefusesInOneLineOrSolvesWithoutACrash) {
  document_campaign(Document::case_document, "document", "AdapterDocumentFuzz.*", budget().reader_inputs / 2);
}

// A Python process per input (0.2-0.5 s each): the command line's count, halved.
TEST(PythonKeywordFuzz, ReturnsOrRaisesValueErrorOrTypeError) {
  if (!python_available()) GTEST_SKIP() << "the Python module is not built";
  const std::vector<std::string> seeds = python_seeds();
  report(campaign(
             "python", std::max<std::size_t>(budget().cli_runs / 2, 1), ".py",
             [&](Rng& rng) { return mutate_python(rng.pick(seeds), rng); },
             [&](const std::string& text) {
               auto problem = check_python(text, budget().cli_limits);
               if (problem) *problem += "\n  keywords: " + excerpt(text, 400);
               return problem;
             }),
         "PythonKeywordFuzz.*");
}

// Issue 46's report target (report_target.hpp): study outputs through `poundbench report`. A
// report is a Python process with matplotlib (1 to 3 s of a core on the tiny studies): the
// corpus is what was found, and the campaign a twentieth of the command line's count.
ChildLimits report_limits() { return {std::max(kReportSeconds, budget().cli_limits.seconds), 2UL << 30}; }

class ReportCorpus : public ::testing::TestWithParam<fs::path> {};

TEST_P(ReportCorpus, ExitsZeroOrTwoWithAWholeFolderOrNone) {
  if (auto problem = check_report(read_file(GetParam()), report_limits())) ADD_FAILURE() << GetParam() << ": " << *problem;
}

INSTANTIATE_TEST_SUITE_P(Fuzz, ReportCorpus, ::testing::ValuesIn(corpus_files("report")), cli_test_name);

TEST(ReportInputFuzz, ExitsZeroOrTwoWithAWholeFolderOrNone) {
  const std::vector<std::string> seeds = report_seeds();
  ASSERT_FALSE(seeds.empty()) << "no corpus/report-seeds/*.csv";
  report(campaign(
             "report", std::max<std::size_t>(budget().cli_runs / 20, 1), ".csv",
             [&](Rng& rng) { return mutate_report(rng.pick(seeds), rng); },
             [&](const std::string& text) {
               auto problem = check_report(text, report_limits());
               if (problem) *problem += "\n  input: " + excerpt(text, 400);
               return problem;
             }),
         "ReportInputFuzz.*");
}

// Issue 46's target (callables.hpp): Python callables as the solver, misbehaving. Each input
// is a Python process sweeping three points, about 1-3 s: a quarter of the command line's
// count. Corpus entries (corpus/callable/*.py: a first '#' line says what each holds) are
// replayed one test each.
ChildLimits callable_limits() {
  ChildLimits limits = budget().cli_limits;
  limits.seconds = std::max(limits.seconds, 20.0) * (POUNDBENCH_FUZZ_SLOW ? 3.0 : 1.0);
  return limits;
}

class CallableCorpus : public ::testing::TestWithParam<fs::path> {};

TEST_P(CallableCorpus, GivesARowPerPointInItsTimeLimit) {
  if (!python_available()) GTEST_SKIP() << "the Python module is not built";
  if (auto problem = check_callable(read_file(GetParam()), callable_limits())) ADD_FAILURE() << GetParam() << ": " << *problem;
}

INSTANTIATE_TEST_SUITE_P(Fuzz, CallableCorpus, ::testing::ValuesIn(corpus_files("callable")), reader_test_name);

TEST(PythonCallableFuzz, GivesARowPerPointInItsTimeLimitWithOneLine) {
  if (!python_available()) GTEST_SKIP() << "the Python module is not built";
  report(campaign(
             "callable", std::max<std::size_t>(budget().cli_runs / 4, 1), ".py", [](Rng& rng) { return make_callable(rng); },
             [](const std::string& text) {
               auto problem = check_callable(text, callable_limits());
               if (problem) *problem += "\n  callable:\n" + excerpt(text, 1200);
               return problem;
             }),
         "PythonCallableFuzz.*");
}

// Issue 46's physical-units target (physical_target.hpp): `run` given physical flags with
// hostile values and missing companions. Each input is one run of a fraction of a second:
// half the command line's count. Corpus entries (corpus/physical/*.args) are replayed one
// test each.
class PhysicalCorpus : public ::testing::TestWithParam<fs::path> {};

TEST_P(PhysicalCorpus, RunsOrRefusesNamingTheFlagGiven) {
  const std::vector<std::string> args = read_args_file(GetParam());
  if (auto problem = check_physical(args, budget().cli_limits))
    ADD_FAILURE() << GetParam() << ": " << *problem << "\n  arguments: " << excerpt(args_text(args), 400);
}

INSTANTIATE_TEST_SUITE_P(Fuzz, PhysicalCorpus, ::testing::ValuesIn(corpus_files("physical")), cli_test_name);

TEST(PhysicalFlagFuzz, RunsOrRefusesNamingTheFlagGiven) {
  report(campaign(
             "physical", std::max<std::size_t>(budget().cli_runs / 2, 1), ".args",
             [](Rng& rng) { return args_text(make_physical_args(rng)); },
             [](const std::string& text) {
               const fs::path tmp = fs::temp_directory_path() / ("poundbench-fuzz-physical-" + std::to_string(::getpid()));
               std::ofstream(tmp, std::ios::binary) << text;
               const std::vector<std::string> args = read_args_file(tmp);
               fs::remove(tmp);
               auto problem = check_physical(args, budget().cli_limits);
               if (problem) *problem += "\n  arguments: " + excerpt(text, 400);
               return problem;
             }),
         "PhysicalFlagFuzz.*");
}

// ---- The harness itself. ----

TEST(FuzzMutator, GivesTheSameInputForTheSameSeedAndIndex) {
  const std::vector<std::string> seeds = reader_seeds(Reader::case_set);
  for (std::uint64_t i = 0; i < 20; ++i) {
    Rng a(input_seed(15, "case_set", i)), b(input_seed(15, "case_set", i));
    EXPECT_EQ(mutate_toml(a.pick(seeds), seeds, a), mutate_toml(b.pick(seeds), seeds, b));
  }
  EXPECT_NE(input_seed(15, "case_set", 1), input_seed(15, "settings", 1));
  EXPECT_NE(input_seed(15, "case_set", 1), input_seed(16, "case_set", 1));
}

TEST(FuzzGenerators, ExpandRepeatAndSeqAndLeaveOtherTextAlone) {
  EXPECT_EQ(expand_generators("a@REPEAT(k,3)@ = [@SEQ(1,2,3)@] a@b.c"), "akkk = [1, 1.5, 2] a@b.c");
  EXPECT_EQ(expand_generators("@REPEAT(x,10000000)@").size(), 10'000'000U);
}

// A hang is work: a child spinning past its CPU limit, or blocked past the wall clock's backstop.
// A child that only waits (for a core on a loaded machine, here for a timer) longer than its
// CPU limit is not one: its input gets the time the machine takes (issue 46's item 12).
TEST(FuzzHarness, SeesASpinningOrBlockedHangACrashAndAStrayLineAsFindings) {
  ChildLimits quick{0.5, 1UL << 30, 2.0};
  const ChildOutcome spinning = run_in_child([] {
    volatile unsigned spin = 0;
    while (true) spin = spin + 1u;
  }, quick);
  EXPECT_TRUE(spinning.timed_out && !spinning.blocked) << spinning.describe();
  const ChildOutcome blocked = run_in_child([] { for (;;) ::pause(); }, quick);
  EXPECT_TRUE(blocked.timed_out && blocked.blocked) << blocked.describe();
  const ChildOutcome waiting = run_in_child([] { ::usleep(1'000'000); }, quick);
  EXPECT_TRUE(waiting.exited && !waiting.timed_out) << waiting.describe();
  const ChildOutcome crash = run_in_child([] { std::abort(); }, quick);
  EXPECT_FALSE(crash.exited);
  EXPECT_EQ(crash.signal, SIGABRT);
  // The command line's own documented refusal passes; a help screen exits 0.
  EXPECT_FALSE(check_cli({"run", "--eps", "2"}, budget().cli_limits));
  EXPECT_FALSE(check_cli({"solvers"}, budget().cli_limits));
  EXPECT_FALSE(check_reader(Reader::case_set, "name = 1", budget().reader_limits));
}

// Issue 46's persistent target (persistent.hpp): persistent external programs misbehaving in
// the stream. Each input is a sweep of four points at a limit of 1 s, 2 to 10 s: an eighth of
// the command line's count. Corpus entries (corpus/persistent/*.py: a first '#' line says what
// each holds) are replayed one test each.
ChildLimits persistent_limits() {
  ChildLimits limits = budget().cli_limits;
  limits.seconds = 120.0 * (POUNDBENCH_FUZZ_SLOW ? 3.0 : 1.0);  // the driver's own bound is 90 s
  return limits;
}

class PersistentCorpus : public ::testing::TestWithParam<fs::path> {};

TEST_P(PersistentCorpus, GivesEveryPointAOneLineRowInTime) {
  if (!persistent_available()) GTEST_SKIP() << "no Python 3 interpreter was found";
  if (auto problem = check_persistent(read_file(GetParam()), persistent_limits())) ADD_FAILURE() << GetParam() << ": " << *problem;
}

INSTANTIATE_TEST_SUITE_P(Fuzz, PersistentCorpus, ::testing::ValuesIn(corpus_files("persistent")), reader_test_name);

TEST(PersistentProgramFuzz, GivesEveryPointAOneLineRowInTime) {
  if (!persistent_available()) GTEST_SKIP() << "no Python 3 interpreter was found";
  report(campaign(
             "persistent", std::max<std::size_t>(budget().cli_runs / 8, 1), ".py",
             [](Rng& rng) { return make_persistent_program(rng); },
             [](const std::string& text) {
               auto problem = check_persistent(text, persistent_limits());
               if (problem) *problem += "\n  program:\n" + excerpt(text, 2000);
               return problem;
             }),
         "PersistentProgramFuzz.*");
}

}  // namespace
}  // namespace pb::fuzz
