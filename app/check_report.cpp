#include "app/check_report.hpp"

#include <algorithm>
#include <iostream>
#include <sstream>

#include "output/output_files.hpp"
#include "frontend/errors.hpp"

namespace pb::app {

namespace {

// Text as XML 1.0 character data or an attribute value: the five markup characters as
// entities, and the control characters XML 1.0 cannot hold at all (a solver's message may
// carry one) as spaces.
std::string xml_text(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        out += static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r' ? ' ' : c;
    }
  }
  return out;
}

}  // namespace

void add_junit_flag(CLI::App& command, std::string& file, std::string_view testcase) {
  command.add_option("--junit", file,
                     "Also write the verdicts as a JUnit XML report to this file (a testcase per " +
                         std::string(testcase) + ", a failure where it failed), for CI systems");
}

void check_junit_target(const std::string& file, bool checked) {
  if (file.empty()) return;
  if (!checked) throw BadInput("--junit: needs --check (it writes --check's verdicts)");
  check_output_target(file, "--junit");
}

std::string junit_xml(std::string_view command, std::span<const Verdict> verdicts) {
  std::vector<std::string> groups;
  for (const Verdict& v : verdicts)
    if (std::find(groups.begin(), groups.end(), v.group) == groups.end()) groups.push_back(v.group);
  const auto failures_in = [&](const std::string* group) {
    std::size_t n = 0, failed = 0;
    for (const Verdict& v : verdicts)
      if (!group || v.group == *group) ++n, failed += v.failure.empty() ? 0 : 1;
    return std::pair{n, failed};
  };
  std::ostringstream xml;
  const auto [total, failed] = failures_in(nullptr);
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"poundbench " << xml_text(command)
      << "\" tests=\"" << total << "\" failures=\"" << failed << "\">\n";
  for (const std::string& group : groups) {
    const auto [n, f] = failures_in(&group);
    xml << "  <testsuite name=\"" << xml_text(group) << "\" tests=\"" << n << "\" failures=\"" << f
        << "\" errors=\"0\" skipped=\"0\">\n";
    for (const Verdict& v : verdicts) {
      if (v.group != group) continue;
      xml << "    <testcase classname=\"" << xml_text(group) << "\" name=\"" << xml_text(v.name) << "\"";
      if (v.failure.empty()) {
        xml << "/>\n";
        continue;
      }
      xml << ">\n      <failure message=\"" << xml_text(v.failure) << "\">" << xml_text(v.failure)
          << "</failure>\n    </testcase>\n";
    }
    xml << "  </testsuite>\n";
  }
  xml << "</testsuites>\n";
  return xml.str();
}

void write_junit(const std::string& file, std::string_view command, std::span<const Verdict> verdicts) {
  if (file.empty()) return;
  const std::string xml = junit_xml(command, verdicts);
  write_atomically(file, [&](std::ostream& out) { out << xml; });
}

int report_check(std::string_view name, std::span<const Verdict> verdicts, std::string_view unit,
                 const std::string& junit) {
  const std::string prefix = "poundbench: " + std::string(name) + " --check: ";
  std::size_t failed = 0;
  for (const Verdict& v : verdicts) {
    if (v.failure.empty()) continue;
    if (++failed <= kListedFailures) std::cerr << prefix << v.name << ": " << v.failure << '\n';
  }
  if (failed > kListedFailures)
    std::cerr << prefix << "and " << failed - kListedFailures << " more failures"
              << (junit.empty() ? std::string(" (--junit FILE lists every one)") : " (every one is in " + junit + ")")
              << '\n';
  std::cerr << prefix << failed << " of " << verdicts.size() << ' ' << unit << " failed\n";
  write_junit(junit, name, verdicts);
  return failed == 0 ? 0 : 1;
}

}  // namespace pb::app
