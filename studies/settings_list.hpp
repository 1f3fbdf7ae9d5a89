#pragma once
// Settings-list files: which solvers, variants and steps a work-precision study runs.
// TOML, one [[run]] table per solver; variant, steps, wh, theta, gamma and tol_scale may
// be lists, and the runs are their cartesian product (variant, theta, gamma, tol_scale
// outermost, the step innermost):
//
//   name = "quick"
//   reference_tol_scale = 0.01        # the "truth": the reference, 100x tighter
//   reference_time_limit = 60         # seconds per truth run (0, the default: none)
//   [[run]]
//   solver = "moreau-jean"
//   theta = [0.5, 1.0]
//   steps = { from = 8, to = 4096 }   # doubling; or a list, or one number
//   [[run]]
//   solver = "moreau-jean"
//   wh = [0.5, 2, 10, 100]            # the step as w_max h instead of steps (not both)
//   time_limit = 10                   # seconds of wall time per run
//
// Keys of [[run]]: solver (required), variant, persistent (true: the external solver's
// persistent variant, as `--persistent`; not with variant), monitor (true/false, true by default: the
// stress study gives the run one more, untimed solve per point with the time-steppers'
// monitor on, for its energy, gap and restitution checks; no solve is timed with it on, and
// the work-precision study has no such solve: StudyOptions::monitor), and every number of a
// solver's Settings as kit/settings_fields.hpp declares it (steps or wh, theta, gamma,
// tol_scale, step_cap, time_limit in seconds per run): a list, or one value; step_cap and
// time_limit take one value.
// In physical units (studies/physical_settings.hpp), never beside their Pi forms in one
// [[run]]: h_s, the fixed step in seconds, instead of steps or wh; k_contact, the contact
// stiffness in N/m (N/m^1.5 for the Hertz family), instead of stiffness; a list, or one
// value each. Mapped to wh and stiffness per case when a study has its cases
// (resolve_physical_settings); stored as given in SettingsList::physical.
// Limits: steps from 1 to 1e9; at most 10,000 settings in the whole list (settings_list.cpp
// says why), counted before expansion.
// The shipped lists are in cases/settings/.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "kit/solver.hpp"
#include "studies/physical_settings.hpp"
#include "sweep/sweep.hpp"

namespace pb {

// what() is one line: "<file>:<line>: <field>: <reason>".
struct SettingsListError : std::runtime_error {
  using std::runtime_error::runtime_error;
};


struct SettingsList {
  std::string name;
  std::string description;
  double reference_tol_scale = 0.01;
  double reference_time_limit = 0;  // seconds of wall time per truth run; 0 = none
  std::vector<SweepRun> runs;  // each with one timed solve; a study sets its repetitions
  // What each run was given in physical units, beside runs (a list built in code may leave
  // it short: a run past its end was given none).
  std::vector<PhysicalSetting> physical;
  // "[[run]] 3: siconos (needs libsiconos-kernel-dev)": the runs of engines this build left
  // out, skipped (a study without them still runs; the caller says so).
  std::vector<std::string> left_out;
};

SettingsList parse_settings_list(std::string_view toml_text, std::string_view source_name);
SettingsList load_settings_list(const std::filesystem::path& file);

}  // namespace pb
