#pragma once
// A test fixture that runs the poundbench binary as a separate process in a fresh
// directory of its own, and what it needs to read back the outputs.

#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <set>
#include <stdexcept>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "rows/row.hpp"
#include "rows/row_read.hpp"

namespace pb {

namespace fs = std::filesystem;

inline const std::string kSource = POUNDBENCH_SOURCE_DIR;  // the project's source tree

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

inline std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::size_t line_count(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// A CSV text read back: its header's columns and each record's fields.
struct CsvTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  explicit CsvTable(const std::string& text) {
    std::istringstream in(text);
    std::string record;
    if (read_csv_record(in, record)) columns = split_csv(record);
    while (read_csv_record(in, record)) rows.push_back(split_csv(record));
  }
  std::size_t column(std::string_view name) const {
    const auto it = std::find(columns.begin(), columns.end(), name);
    if (it == columns.end()) throw std::logic_error("no column " + std::string(name));
    return static_cast<std::size_t>(it - columns.begin());
  }
  std::string& at(std::size_t row, std::string_view name) { return rows.at(row).at(column(name)); }
  // The table with these columns emptied: what two runs of one sweep have in common
  // (without(kTimingColumns), rows/row.hpp).
  template <typename Names = std::initializer_list<std::string_view>>
  CsvTable without(const Names& names) const {
    CsvTable out = *this;
    for (std::string_view name : names)
      for (auto& row : out.rows) row.at(column(name)).clear();
    return out;
  }
  // One record as CSV again.
  static std::string line(const std::vector<std::string>& fields) {
    std::string text;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      if (i) text += ',';  // not `"," + field`: GCC 12 misreports that at -O3 (-Wrestrict)
      text += csv_field(fields[i]);
    }
    return text;
  }
};

// A case set of 6 quick points (two Pi2 spectra of 3 points of a pair).
inline constexpr const char* kTinySet = R"(name = "tiny"
[[family]]
name = "pair"
scene = "pair"
pulse = ["sine", "cosine"]
directivity = "normal"
eps = 0.5
pi3 = 0.5
pi5 = 0.75
pi6 = 1
pi2 = { from = 0.5, to = 2, points = 3, spacing = "log" }
)";

// Starts poundbench with `args` (an argument vector, no shell) in `dir`, stdout to `out`,
// stderr to `err`, SIGINT at its default whatever the test runner inherited (so that a
// test can interrupt it); returns its pid.
inline pid_t spawn_poundbench(std::vector<std::string> args, const fs::path& dir, const fs::path& out,
                              const fs::path& err) {
  args.insert(args.begin(), POUNDBENCH_EXE);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t signals, none;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigemptyset(&none);
  posix_spawnattr_setsigdefault(&attr, &signals);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (spawned != 0) throw std::runtime_error("cannot start poundbench");
  return pid;
}

// Every test works in a fresh directory of its own, which it removes afterwards.
class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("poundbench-cli-" + std::to_string(::getpid()) + "-" + test->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path file(const std::string& name) const { return dir_ / name; }

  void write(const std::string& name, const std::string& text) const { std::ofstream(file(name)) << text; }

  // Runs poundbench with `args` (a shell word list) in the test directory; `launcher`
  // comes before the program (an mpiexec command line).
  Outcome run(const std::string& args, const std::string& launcher = "") const {
    const std::string command = "cd '" + dir_.string() + "' && " + launcher + " '" POUNDBENCH_EXE "' " + args +
                                " > stdout.txt 2> stderr.txt";
    const int status = std::system(command.c_str());
    Outcome o;
    o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    o.out = read_text(file("stdout.txt"));
    o.err = read_text(file("stderr.txt"));
    fs::remove(file("stdout.txt"));
    fs::remove(file("stderr.txt"));
    return o;
  }

  std::set<std::string> files() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.insert(entry.path().filename().string());
    return names;
  }

  fs::path dir_;
};

}  // namespace pb
