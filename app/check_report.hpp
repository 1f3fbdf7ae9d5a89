#pragma once
// What a check of the command line says, for people and for CI systems: `spectrum --check`,
// `workprecision --check`, `stress --check`, `baseline --check` and `compare` each judge a
// list of things (a family, a summary row, a comparison line) and end with
//
//   - on stderr (the sweeps), one line per failure, the first kListedFailures of them, then
//     one line that counts them: "poundbench: stress --check: 1 of 4 rows failed";
//   - with --junit FILE, a JUnit XML report: a <testsuite> per group (the command, or a
//     baseline file), a <testcase> per thing judged, a <failure> with the reason where it
//     failed. Jenkins, GitLab and GitHub's test reporters read it. Written through a
//     temporary file as every output is, after the command's own outputs.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

namespace pb::app {

struct Verdict {
  std::string group;    // the JUnit testsuite (and classname): "workprecision", a baseline file
  std::string name;     // what was judged: a row's label, a family
  std::string failure;  // why it failed, one line; "" when it passed
};

// Failure lines printed on stderr before the count; the rest are counted in one line (the
// JUnit file and the outputs have every one). A sweep whose 23 820 points failed would
// otherwise print 23 820 lines.
inline constexpr std::size_t kListedFailures = 20;

// --junit FILE on a command that judges (its help names what a testcase is).
void add_junit_flag(CLI::App& command, std::string& file, std::string_view testcase);

// Before anything runs: a --junit FILE needs a check to report (`checked`: --check was
// given) and a place to be written (check_output_target); throws BadInput otherwise.
void check_junit_target(const std::string& file, bool checked);

// The JUnit XML of a list of verdicts (their groups in order of first appearance).
std::string junit_xml(std::string_view command, std::span<const Verdict> verdicts);

// Writes junit_xml to `file` (nothing when `file` is empty); throws std::runtime_error on a
// failed write.
void write_junit(const std::string& file, std::string_view command, std::span<const Verdict> verdicts);

// A sweep's --check: the failures and their count on stderr ("poundbench: <name> --check: ..."),
// `unit` naming what was counted ("rows", "families"), and the JUnit file when `junit` is
// given. Returns the exit code: 1 when any failed, 0 otherwise.
int report_check(std::string_view name, std::span<const Verdict> verdicts, std::string_view unit,
                 const std::string& junit);

}  // namespace pb::app
