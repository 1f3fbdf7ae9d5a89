#include "app/solvers_command.hpp"

#include <algorithm>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/fields.hpp"
#include "kit/solver.hpp"
#include "solvers/registry.hpp"

namespace pb::app {

namespace {

// A variant as listed: its name, its label ("(default)" for the reference's nameless
// default, "name (default)" for another solver's), what it is and the settings it uses.
struct Listed {
  std::string_view name;
  std::string label;
  std::string summary;
  std::vector<std::string_view> settings;
  std::vector<SettingsWhen> when;  // the settings it uses only under another choice of a name
};

std::vector<Listed> listed_variants(const SolverInfo& solver) {
  std::vector<Listed> out;
  for (const VariantInfo& v : solver.variants()) {
    std::string label = v.name.empty() ? "(default)" : std::string(v.name);
    if (out.empty() && !v.name.empty()) label += " (default)";
    out.push_back({v.name, label, v.summary, settings_used(solver, v.name), settings_used_when(solver, v.name)});
  }
  return out;
}

std::string flags_of(const std::vector<std::string_view>& settings) {
  std::string text;
  for (std::string_view s : settings) text += (text.empty() ? "" : " ") + flag_of(s);
  return text.empty() ? "none" : text;
}

// "settings: A" when every variant uses the same ones, else "settings: v1, v2: A; v3: B".
std::string settings_line(const std::vector<Listed>& variants) {
  std::vector<std::pair<std::vector<std::string_view>, std::string>> groups;  // settings, the variants' labels
  for (const Listed& v : variants) {
    const auto same = [&](const auto& group) { return group.first == v.settings; };
    const auto group = std::find_if(groups.begin(), groups.end(), same);
    if (group == groups.end())
      groups.emplace_back(v.settings, v.label);
    else
      group->second += ", " + v.label;
  }
  if (groups.size() == 1) return "settings: " + flags_of(groups.front().first);
  std::string line;
  for (const auto& [settings, labels] : groups) line += (line.empty() ? "settings: " : "; ") + labels + ": " + flags_of(settings);
  return line;
}

void print_text() {
  std::size_t width = 0, variant_width = 0;
  for (const SolverInfo& s : solvers()) {
    width = std::max(width, s.name.size());
    for (const Listed& v : listed_variants(s)) variant_width = std::max(variant_width, v.label.size());
  }
  for (const SolverInfo& s : solvers()) {
    const std::vector<Listed> variants = listed_variants(s);
    std::cout << s.name << std::string(width + 2 - s.name.size(), ' ') << s.summary << '\n';
    std::cout << "    variants:\n";
    for (const Listed& v : variants)
      std::cout << "      " << v.label << std::string(variant_width + 2 - v.label.size(), ' ') << v.summary << '\n';
    std::cout << "    " << settings_line(variants) << '\n';
    // Each choice once, with the settings some variant uses under it.
    std::vector<SettingsWhen> when;
    for (const Listed& v : variants)
      for (const SettingsWhen& w : v.when) {
        const auto same = std::find_if(when.begin(), when.end(),
                                       [&](const SettingsWhen& o) { return o.field == w.field && o.choice == w.choice; });
        if (same == when.end())
          when.push_back(w);
        else
          for (std::string_view f : w.settings)
            if (std::find(same->settings.begin(), same->settings.end(), f) == same->settings.end())
              same->settings.push_back(f);
      }
    for (const SettingsWhen& w : when)
      std::cout << "    with " << flag_of(w.field) << ' ' << w.choice << ": " << flags_of(w.settings) << '\n';
  }
  std::cout << "Every solver also takes the limits of a run, --step-cap and --time-limit.\n";
}

void print_json() {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const SolverInfo& s : solvers()) {
    nlohmann::ordered_json variants = nlohmann::ordered_json::array();
    for (const Listed& v : listed_variants(s)) {
      nlohmann::ordered_json when = nlohmann::ordered_json::array();
      for (const SettingsWhen& w : v.when) when.push_back({{"field", w.field}, {"value", w.choice}, {"settings", w.settings}});
      variants.push_back({{"name", v.name}, {"default", variants.empty()}, {"summary", v.summary},
                          {"settings", v.settings}, {"settings_when", when}});
    }
    list.push_back({{"name", s.name}, {"summary", s.summary}, {"reference", s.reference}, {"variants", variants}});
  }
  std::cout << nlohmann::ordered_json{{"solvers", list}}.dump() << '\n';
}

}  // namespace

CLI::App* add_solvers_command(CLI::App& app, SolversFlags& flags) {
  CLI::App* command = app.add_subcommand("solvers", "List the solvers, their variants and the settings each uses");
  command->add_flag("--json", flags.json, "One JSON object: solvers[], each with its variants[] and their settings[]");
  return command;
}

int solvers_command(const SolversFlags& flags) {
  if (flags.json)
    print_json();
  else
    print_text();
  return 0;
}

}  // namespace pb::app
