#include "app/report_command.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "app/version.hpp"

namespace pb::app {

namespace fs = std::filesystem;

namespace {

// The generator: installed beside the binary, else the source tree of this build (both
// paths from CMake: POUNDBENCH_INSTALLED_REPORTS relative to the binary's folder).
fs::path find_generator() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  std::vector<fs::path> places;
  if (!ec) places.push_back(exe.parent_path() / POUNDBENCH_INSTALLED_REPORTS / "report.py");
  places.push_back(fs::path(POUNDBENCH_SOURCE_REPORTS) / "report.py");
  for (const fs::path& p : places)
    if (fs::is_regular_file(p, ec)) return p.lexically_normal();
  std::string looked;
  for (const fs::path& p : places) looked += (looked.empty() ? "" : " and ") + p.lexically_normal().string();
  throw std::runtime_error("report: the report generator is not found (looked for " + looked +
                           "): install poundbench with `cmake --install`, or run the binary of a build directory");
}

bool executable(const fs::path& p) { return ::access(p.c_str(), X_OK) == 0 && !fs::is_directory(p); }

fs::path find_python() {
  if (const char* chosen = std::getenv("POUNDBENCH_PYTHON"); chosen && *chosen) {
    if (!executable(chosen))
      throw std::runtime_error(std::string("report: POUNDBENCH_PYTHON=") + chosen + ": not an executable file");
    return chosen;
  }
  if (executable("/usr/bin/python3")) return "/usr/bin/python3";
  if (const char* path = std::getenv("PATH")) {
    std::istringstream dirs(path);
    for (std::string dir; std::getline(dirs, dir, ':');)
      if (!dir.empty() && executable(fs::path(dir) / "python3")) return fs::path(dir) / "python3";
  }
  throw std::runtime_error(
      "report: no Python 3 interpreter (neither /usr/bin/python3 nor python3 on PATH; Debian: python3 "
      "python3-matplotlib, which scripts/setup.sh installs)");
}

}  // namespace

CLI::App* add_report_command(CLI::App& app, ReportFlags& flags) {
  CLI::App* command = app.add_subcommand(
      "report", "Write a study's report: markdown, figures and an HTML page that works offline (Python, matplotlib)");
  command
      ->add_option("STUDY", flags.study,
                   "A study's output: `workprecision --out`, `stress --out`, or `spectrum`'s rows (CSV)")
      ->required();
  command->add_option("--points", flags.points,
                      "The study's per-run rows (`workprecision --points`, `stress --points`): spectra, scenes, "
                      "errors over impacting points, failure messages");
  command->add_option("--out", flags.out, "The report's folder (created): README.md, figures/, report.html")
      ->required();
  command->add_option("--title", flags.title, "The report's title (default: the kind of study and the file's name)");
  return command;
}

int report_command(const ReportFlags& flags) {
  const fs::path python = find_python();
  const fs::path generator = find_generator();
  const std::string made_by = std::string("poundbench ") + kVersion + " (commit " + kCommit + ") report";
  std::vector<std::string> args = {python.string(), generator.string(), flags.study, "--out", flags.out,
                                   "--made-by", made_by};
  if (!flags.points.empty()) args.insert(args.end(), {"--points", flags.points});
  if (!flags.title.empty()) args.insert(args.end(), {"--title", flags.title});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // Handed over: the generator's exit code and lines are the command's.
  ::execv(python.c_str(), argv.data());
  throw std::runtime_error("report: cannot run " + python.string() + ": " + std::strerror(errno));
}

}  // namespace pb::app
