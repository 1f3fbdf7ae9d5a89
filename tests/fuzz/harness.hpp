#pragma once
// The fuzz targets of issue 15 and the properties they must keep:
//
// * the case-set and settings readers (parse_case_set, parse_settings_list) return a value
//   or throw their own error type with a one-line message that names the file and is at
//   most kMaxMessage characters; anything else (another exception, a crash, a sanitizer
//   report, more time or memory than the limits) is a finding;
// * the poundbench command exits 0 or 2, or 1 having printed a result (run's solver did not
//   reach t_end, compare/baseline found a difference); never a signal, never a hang; on
//   exit 2 stderr is one line and stdout is empty, and no file is left behind; on success
//   the only new files are the outputs it was asked for; and an input that is bad on its
//   face (an empty argument, a negative, NaN or infinite value of a flag whose domain is
//   >= 0) is refused with exit 2.
//
// Each input runs in a child process (child.hpp), so a finding never stops the campaign.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tests/fuzz/child.hpp"

namespace pb::fuzz {

namespace fs = std::filesystem;

inline constexpr std::size_t kMaxMessage = 300;

enum class Reader { case_set, settings };

// What a run is allowed, and how much of it the campaigns do; from the build (slow:
// Debug or sanitizers) and the environment (scripts/fuzz.sh).
struct Budget {
  std::uint64_t seed = 15;
  std::size_t reader_inputs = 200;  // per reader
  std::size_t cli_runs = 40;
  double seconds = 0;               // > 0: run each campaign this long instead of counting
  std::size_t max_failures = 5;     // a campaign stops after this many findings
  std::optional<std::uint64_t> only_index;  // replay one input
  fs::path failures_dir;            // where failing inputs are written (empty: nowhere)
  ChildLimits reader_limits{2, 2UL << 30};
  ChildLimits cli_limits{5, 2UL << 30};

  static Budget from_build_and_environment();
};

// The property `text` violates when read by `reader`, or nothing.
std::optional<std::string> check_reader(Reader reader, const std::string& text, const ChildLimits& limits);

// The property a run of poundbench with `args` violates, or nothing. The run happens in a
// fresh directory holding the fixtures (tiny.toml, tiny-settings.toml), which is removed
// afterwards; "@SOURCE@" in an argument is the source tree.
std::optional<std::string> check_cli(const std::vector<std::string>& args, const ChildLimits& limits);

// The seeds: the shipped case sets or settings lists (and the fixtures), as text.
std::vector<std::string> reader_seeds(Reader reader);
// Short command lines, one per subcommand and scene, each a fraction of a second.
std::vector<std::vector<std::string>> cli_seeds();

// A corpus file of command-line arguments: one per line ('' is an empty line), lines that
// start with "#" are comments.
std::vector<std::string> read_args_file(const fs::path& file);
std::string args_text(const std::vector<std::string>& args);  // the same format, to write one

// What a one-line error message must be: one line of at most kMaxMessage characters; `size`
// is every byte written, `what` "message" or "stderr". Nothing when it is one.
std::optional<std::string> one_line_problem(const std::string& message, std::size_t size, const std::string& what);
// Every file and folder under `dir`, relative to it.
std::set<std::string> listing(const fs::path& dir);

std::string read_file(const fs::path& file);
std::vector<fs::path> corpus_files(const std::string& kind);  // tests/fuzz/corpus/<kind>/*, sorted
std::string excerpt(const std::string& text, std::size_t most = 160);

}  // namespace pb::fuzz
