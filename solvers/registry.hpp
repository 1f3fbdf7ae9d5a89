#pragma once
// The registry: every solver by name (solvers/registry.cpp holds one row per solver, and a new
// solver is its folder and that row), and the rules that hold for all of them.

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "kit/buildings_result.hpp"
#include "kit/separation.hpp"
#include "kit/solver.hpp"

namespace pb {

std::span<const SolverInfo> solvers();
const SolverInfo* find_solver(std::string_view name);
// For an engine this build left out (its Debian package was not found: CMakeLists.txt), the
// package it needs, e.g. "libsiconos-kernel-dev"; "" for a solver that is built or unknown.
std::string_view left_out_needs(std::string_view name);
const SolverInfo& reference_solver();
// Whether some registered solver declares an own setting (SolverInfo::own_settings) of this
// name: a flag, a settings-list key and a Python keyword of that name exist.
bool is_own_setting(std::string_view name);
// The fields of kit/settings_fields.hpp that a variant of the solver uses: those whose
// value changes what its describe() says (the settings column of its rows), in the table's
// order. The limits (step_cap, time_limit) are every solver's and in no describe().
std::vector<std::string_view> settings_used(const SolverInfo& solver, std::string_view variant);
// The settings a variant uses only where one of the names it uses takes another of its choices
// (SettingField::choices; the solver's check accepting it): compliant's steps, wh, h_s under
// integrator newmark. Per such choice, the fields it adds to settings_used's.
struct SettingsWhen {
  std::string_view field, choice;
  std::vector<std::string_view> settings;
};
std::vector<SettingsWhen> settings_used_when(const SolverInfo& solver, std::string_view variant);
// One rule for every solver (issue 12): a setting given but not used is refused, so that no
// flag or key is accepted and silently ignored (`mujoco --stiffness 1e4`, `compliant --theta
// nan`). A field of kit/settings_fields.hpp is used by these settings when its value
// changes what the solver's describe() says (the other fields as given): describe() names
// every setting that changes a run, as the rows' settings column. Given means `given(name)`
// says so, or, without `given`, a value other than Settings{}'s (NaN included). The limits
// (step_cap, time_limit) are every solver's. Every check of the registry applies it with
// values alone (a settings list, the library); the command line and the Python module
// apply it to the flags given too, after that check: with `given`, only a field given at its
// default value is looked at (the check saw the others). Returns "field: not used by ..." or "".
using GivenSetting = std::function<bool(std::string_view field)>;
std::string unused_setting(const SolverInfo& solver, const Settings& settings, const GivenSetting& given = {});
// Pi1 of body 0 with every contact removed, by the reference; only the time limit and stop
// flag of `limits` are used.
double no_contact_pi1(const System& system, const Settings& limits);
// The motion of every body with every contact removed, by the reference (kit/separation.hpp).
FreeMotion free_motion(const System& system, const Settings& limits);
// The buildings scene's the same, by its reference (solvers/buildings_reference/reference.hpp):
// the floors' and storeys' peaks, and per contact how far its floors come together and apart.
buildings::BuildingsResult buildings_free_motion(const BuildingScene& scene, const Settings& limits);

}  // namespace pb
