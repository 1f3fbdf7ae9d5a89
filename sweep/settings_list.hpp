#pragma once
// Settings-list files: which solvers, variants and steps a work-precision study runs.
// TOML, one [[run]] table per solver; every key may be a list, and the runs are the
// cartesian product (variant, theta, gamma, tol_scale outermost, steps innermost):
//
//   name = "quick"
//   reference_tol_scale = 0.01        # the "truth": the reference, 100x tighter
//   [[run]]
//   solver = "moreau-jean"
//   theta = [0.5, 1.0]
//   steps = { from = 8, to = 4096 }   # doubling; or a list, or one number
//
// Keys of [[run]]: solver (required), variant, steps, theta, gamma, tol_scale, step_cap.
// The shipped lists are in cases/settings/.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "solvers/solver.hpp"

namespace pb {

// what() is one line: "<file>:<line>: <field>: <reason>".
struct SettingsListError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct RunSpec {
  std::string solver;
  Settings settings;
};

struct SettingsList {
  std::string name;
  std::string description;
  double reference_tol_scale = 0.01;
  std::vector<RunSpec> runs;
};

SettingsList parse_settings_list(std::string_view toml_text, std::string_view source_name);
SettingsList load_settings_list(const std::filesystem::path& file);

}  // namespace pb
