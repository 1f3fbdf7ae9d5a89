#include "tests/fuzz/harness.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "cases/case_set.hpp"
#include "studies/settings_list.hpp"

namespace pb::fuzz {

namespace {

// A tiny case set and settings list for the command-line runs: two points, each a
// fraction of a second through any solver.
constexpr const char* kTinyCaseSet = R"(name = "tiny"
[[family]]
name = "wall"
scene = "wall"
pulse = "sine"
directivity = "normal"
eps = 0.5
pi3 = 0.5
pi2 = 1
[[family]]
name = "pair"
scene = "pair"
pulse = "cosine"
directivity = "reverse"
eps = 1
pi3 = 0.5
pi5 = 1.33
pi6 = 2
pi2 = [0.5, 2]
)";

constexpr const char* kTinySettings = R"(name = "tiny"
reference_tol_scale = 0.1
reference_time_limit = 2
[[run]]
solver = "moreau-jean"
steps = { from = 16, to = 32 }
time_limit = 2
[[run]]
solver = "event-driven"
tol_scale = 100
time_limit = 2
)";

std::optional<std::string> env(const char* name) {
  const char* value = std::getenv(name);
  if (!value || !*value) return std::nullopt;
  return std::string(value);
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

std::size_t lines_in(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// Flags whose value the command documents as a number >= 0 (docs/cli.md): poundbench must
// refuse a negative, NaN or infinite one (--kick may be negative; --pi terms, a_p, w_p and
// n_free must be > 0 too, which validate() checks and a run then shows).
bool non_negative_number_flag(const std::string& flag) {
  static const std::set<std::string> flags = {
      "--pi2", "--pi3", "--eps", "--pi5", "--pi6", "--pi7", "--pi8", "--xi", "--n-free", "--a-p", "--w-p",
      "--bodies", "--point", "--steps", "--wh", "--tol-scale", "--step-cap", "--time-limit", "--samples",
      "--threads", "--tolerance", "--tp", "--stiffness", "--rtol", "--contact-steps", "--projection-tol",
      "--repetitions", "--max-error"};
  return flags.count(flag) > 0;
}

// Why these arguments must be refused (exit 2), if they must: an empty argument (no flag
// takes an empty value, and no command an empty file name), or a number flag given a
// value outside its domain. The mutations produce both often; today some are accepted.
std::optional<std::string> must_refuse(const std::vector<std::string>& args) {
  // --help wins over everything else on the line (CLI11 prints the help and exits 0).
  if (std::find_if(args.begin(), args.end(), [](const std::string& a) { return a == "--help" || a == "-h"; }) !=
      args.end())
    return std::nullopt;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i].empty()) return "the empty argument " + std::to_string(i) + (i ? " (after " + args[i - 1] + ")" : "");
    if (i + 1 >= args.size() || !non_negative_number_flag(args[i])) continue;
    const std::string& value = args[i + 1];
    char* end = nullptr;
    const double x = std::strtod(value.c_str(), &end);
    if (end == value.c_str() || *end) continue;  // not a number: CLI11's to refuse, and it does
    if (!std::isfinite(x) || x < 0) return args[i] + " " + value;
  }
  return std::nullopt;
}

}  // namespace

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    names.insert(fs::relative(it->path(), dir).string());
  return names;
}

std::optional<std::string> one_line_problem(const std::string& message, std::size_t size, const std::string& what) {
  if (size == 0) return what + " is empty";
  const std::size_t body = message.back() == '\n' ? message.size() - 1 : message.size();
  if (message.find('\n') < body) return what + " is " + std::to_string(lines_in(message) + 1) + " lines: " + excerpt(message);
  if (size > kMaxMessage + 1)
    return what + " is " + std::to_string(size) + " characters (> " + std::to_string(kMaxMessage) + "): " +
           excerpt(message);
  return std::nullopt;
}

Budget Budget::from_build_and_environment() {
  Budget b;
#if POUNDBENCH_FUZZ_SLOW
  // Debug with sanitizers: inputs cost ten times as much, so fewer, with more time each.
  b.reader_inputs = 50;
  b.cli_runs = 10;
  b.reader_limits.seconds = 20;
  b.cli_limits.seconds = 15;
#endif
  if (auto v = env("POUNDBENCH_FUZZ_SEED")) b.seed = std::stoull(*v);
  if (auto v = env("POUNDBENCH_FUZZ_INPUTS")) b.reader_inputs = b.cli_runs = std::stoull(*v);
  if (auto v = env("POUNDBENCH_FUZZ_SECONDS")) b.seconds = std::stod(*v);
  if (auto v = env("POUNDBENCH_FUZZ_MAX_FAILURES")) b.max_failures = std::stoull(*v);
  if (auto v = env("POUNDBENCH_FUZZ_INDEX")) b.only_index = std::stoull(*v);
  if (auto v = env("POUNDBENCH_FUZZ_FAILURES")) b.failures_dir = *v;
  if (auto v = env("POUNDBENCH_FUZZ_RUN_SECONDS")) b.cli_limits.seconds = b.reader_limits.seconds = std::stod(*v);
  return b;
}

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string excerpt(const std::string& text, std::size_t most) {
  std::string out = text.substr(0, most);
  std::replace(out.begin(), out.end(), '\n', '|');
  if (text.size() > most) out += "... (" + std::to_string(text.size()) + " chars)";
  return out;
}

std::vector<fs::path> corpus_files(const std::string& kind) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(fs::path(POUNDBENCH_FUZZ_CORPUS) / kind))
    if (entry.is_regular_file() && entry.path().filename().string().front() != '.') files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::string> read_args_file(const fs::path& file) {
  const std::string text = read_file(file);
  std::vector<std::string> args;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    if (line.rfind('#', 0) != 0) args.push_back(line);
    start = end + 1;
  }
  return args;
}

std::string args_text(const std::vector<std::string>& args) {
  std::string text = "# poundbench arguments, one per line (an empty line is an empty argument)\n";
  for (const std::string& a : args) text += a + '\n';
  return text;
}

std::optional<std::string> check_reader(Reader reader, const std::string& text, const ChildLimits& limits) {
  const ChildOutcome o = report_in_child(
      [&]() -> std::string {
        try {
          const std::size_t n = reader == Reader::case_set ? parse_case_set(text, "fuzz.toml").cases.size()
                                                           : parse_settings_list(text, "fuzz.toml").runs.size();
          return "OK " + std::to_string(n);
        } catch (const CaseSetError& e) {
          return reader == Reader::case_set ? std::string("ERR ") + e.what()
                                            : std::string("EXC pb::CaseSetError: ") + e.what();
        } catch (const SettingsListError& e) {
          return reader == Reader::settings ? std::string("ERR ") + e.what()
                                            : std::string("EXC pb::SettingsListError: ") + e.what();
        }
      },
      limits);
  if (!o.exited || o.exit_code != 0 || !sanitizer_line(o.err).empty())
    return o.describe() + (o.err.empty() ? "" : "; stderr: " + excerpt(o.err, 300));
  if (o.out.rfind("EXC ", 0) == 0) return "threw another exception: " + excerpt(o.out.substr(4), 200);
  if (o.out.rfind("ERR ", 0) == 0) {
    const std::string message = o.out.substr(4);
    if (auto bad = one_line_problem(message, o.out_size - 4, "message")) return bad;
    if (message.rfind("fuzz.toml", 0) != 0) return "message does not start with the file name: " + excerpt(message);
  } else if (o.out.rfind("OK ", 0) != 0) {
    return "no outcome reported; stdout: " + excerpt(o.out);
  }
  if (!o.err.empty()) return "wrote to stderr: " + excerpt(o.err);
  return std::nullopt;
}

std::optional<std::string> check_cli(const std::vector<std::string>& given, const ChildLimits& limits) {
  static std::atomic<int> counter{0};
  const fs::path dir = fs::temp_directory_path() /
                       ("poundbench-fuzz-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "tiny.toml") << kTinyCaseSet;
  std::ofstream(dir / "tiny-settings.toml") << kTinySettings;
  // FIFOs nobody writes to (issue 33): every input must refuse one rather than wait, the
  // partial file of `--out p.csv` too.
  ::mkfifo((dir / "fifo").c_str(), 0644);
  ::mkfifo((dir / "p.csv.partial").c_str(), 0644);
  // Records as copies in the run's directory: a mutation may make any file value an output
  // (--record renamed --out), and a path into the source tree would then be overwritten.
  fs::copy_file(fs::path(POUNDBENCH_SOURCE_DIR) / "cases/records/real/AZF225.AT2", dir / "rec.at2");
  std::ofstream(dir / "rec.csv") << "t, a_g\n0, 0\n0.05, 1.5\n0.1, -2\n0.15, 0.5\n0.2, 0\n";
  std::vector<std::string> args;
  for (const std::string& a : given) args.push_back(replace_all(a, "@SOURCE@", POUNDBENCH_SOURCE_DIR));

  const std::set<std::string> before = listing(dir);
  const ChildOutcome o = run_program(POUNDBENCH_EXE, args, dir, limits);
  const std::set<std::string> after = listing(dir);
  fs::remove_all(dir);

  std::vector<std::string> added;
  std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(added));
  const std::string first_err = o.err.substr(0, o.err.find('\n'));
  if (!o.exited || !sanitizer_line(o.err).empty())
    return o.describe() + (o.err.empty() ? "" : "; stderr: " + excerpt(o.err, 300));
  if (o.exit_code == 2) {
    if (auto bad = one_line_problem(o.err, o.err_size, "stderr")) return "exit 2: " + *bad;
    if (o.err.rfind("poundbench: ", 0) != 0) return "exit 2: stderr does not start with 'poundbench: ': " + excerpt(o.err);
    if (o.out_size) return "exit 2: stdout not empty: " + excerpt(o.out);
    if (!added.empty()) return "exit 2: left a file behind: " + added.front();
    return std::nullopt;
  }
  if (auto reason = must_refuse(args))
    return "accepted " + *reason + " (" + o.describe() + "); a bad input must exit 2" +
           (o.out.empty() ? "" : "; stdout: " + excerpt(o.out, 120));
  // Exit 1 is documented only with a result printed: a run that did not reach t_end, a
  // comparison that found differences.
  const bool printed_result = o.exit_code == 1 && o.out_size > 0 && o.err_size == 0;
  if (o.exit_code != 0 && !printed_result)
    return o.describe() + (o.err.empty() ? "" : "; stderr: " + excerpt(o.err, 300));
  // Success: only the outputs asked for may be new.
  std::set<std::string> requested;
  for (std::size_t i = 0; i + 1 < args.size(); ++i)
    if (args[i] == "--out" || args[i] == "--points" || args[i] == "--history")
      requested.insert(fs::path(args[i + 1]).lexically_normal().string());
  for (const std::string& file : added) {
    if (fs::is_directory(dir / file) || requested.count(file)) continue;
    return o.describe() + ": left a file that was not asked for: " + file;
  }
  return std::nullopt;
}

std::vector<std::string> reader_seeds(Reader reader) {
  const fs::path source = POUNDBENCH_SOURCE_DIR;
  std::vector<std::string> seeds = {reader == Reader::case_set ? kTinyCaseSet : kTinySettings};
  const fs::path dir = source / "cases" / (reader == Reader::case_set ? "sets" : "settings");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());  // a fixed order: the seeds' indices are part of a reproduction
  for (const fs::path& f : files) seeds.push_back(read_file(f));
  return seeds;
}

std::vector<std::vector<std::string>> cli_seeds() {
  const std::vector<std::string> wall = {"--scene", "wall", "--pulse", "sine", "--directivity", "normal",
                                         "--pi2",   "1",    "--pi3",   "0.5",  "--eps",         "0.5"};
  std::vector<std::vector<std::string>> seeds;
  auto add = [&](std::vector<std::string> head, const std::vector<std::string>& tail = {}) {
    head.insert(head.end(), tail.begin(), tail.end());
    seeds.push_back(std::move(head));
  };
  add({"run"}, wall);
  add({"run", "--scene", "pair", "--pulse", "cosine", "--directivity", "reverse", "--pi2", "0.8", "--pi3", "0.5",
       "--eps", "0.5", "--pi5", "0.5", "--pi6", "1", "--json"});
  add({"run", "--scene", "row3", "--pulse", "sine", "--directivity", "normal", "--pi2", "2", "--pi3", "0.2", "--eps",
       "1", "--pi5", "0.75", "--pi6", "1", "--pi7", "1.33", "--pi8", "2", "--solver", "moreau-jean", "--steps", "64",
       "--theta", "0.5", "--gamma", "0.5"});
  add({"run", "--scene", "chain", "--bodies", "4", "--kick", "1", "--pulse", "sine", "--directivity", "normal",
       "--pi2", "1", "--pi3", "0", "--eps", "1", "--pi5", "1", "--pi6", "1", "--solver", "moreau-jean", "--steps",
       "32"});
  add({"run", "--history", "history.csv", "--samples", "50", "--xi", "0.1", "--n-free", "2", "--a-p", "2", "--w-p",
       "3"},
      wall);
  add({"run", "--case-file", "tiny.toml", "--point", "1", "--tol-scale", "10", "--step-cap", "100000"});
  add({"spectrum", "tiny.toml", "--out", "out.csv", "--threads", "1", "--solver", "moreau-jean", "--wh", "0.5"});
  add({"workprecision", "tiny.toml", "--settings", "tiny-settings.toml", "--out", "wp.csv", "--points",
       "wp-points.csv", "--threads", "1"});
  add({"stress", "tiny.toml", "--settings", "tiny-settings.toml", "--out", "stress.csv", "--threads", "1"});
  add({"baseline", "tiny.toml", "--settings", "tiny-settings.toml", "--out", "base.csv", "--threads", "1"});
  add({"compare", "@SOURCE@/tests/baselines/smoke.csv", "--baseline", "@SOURCE@/tests/baselines/smoke.csv",
       "--tolerance", "1e-3"});
  // issue 33: a real record, an engine at a large step, outputs beside their inputs
  add({"run", "--scene", "pair", "--pulse", "record", "--record", "rec.at2", "--tp",
       "0.5", "--directivity", "normal", "--pi2", "1", "--pi3", "0.5", "--eps", "0.5", "--pi5", "2", "--pi6", "1",
       "--json"});
  add({"run", "--solver", "ode", "--wh", "2"}, wall);
  add({"spectrum", "tiny.toml", "--out", "tiny.csv", "--threads", "1", "--solver", "compliant", "--stiffness", "1e4"});
  add({"solvers"});
  return seeds;
}

}  // namespace pb::fuzz
