#pragma once
// Every number of a solver's Settings, declared once (as cases/fields.hpp declares a
// Case's): its name (the settings-list key and, with '_' as '-', the command-line flag),
// its member and its help. The flags of `run` and `spectrum`, and the naming of a field in
// a solver's check() message as its flag, are made from this table.
//
// A field is a number (number, integer or count set) or a name (text set). Settings::variant
// (a name every solver has) and Settings::monitor (a switch of the studies) are not in the
// table; Settings::history_samples is `run --samples`.

#include <array>
#include <optional>
#include <span>
#include <string_view>

#include "kit/solver.hpp"

namespace pb {

struct SettingField {
  std::string_view name;
  double Settings::* number;  // one of these four is set
  int Settings::* integer;
  long Settings::* count;
  std::string_view help;
  std::string Settings::* text = nullptr;
  // A name's values where they are a fixed few (the default first): `poundbench solvers` lists
  // the settings a solver uses under each (compliant's --steps under --integrator newmark).
  std::span<const std::string_view> choices{};

  // A number's value (not for a name).
  double get(const Settings& s) const {
    return number ? s.*number : integer ? static_cast<double>(s.*integer) : static_cast<double>(s.*count);
  }
  // A whole-number field takes the value as it is: the caller has checked it is whole.
  void set(Settings& s, double value) const {
    if (number) s.*number = value;
    else if (integer) s.*integer = static_cast<int>(value);
    else s.*count = static_cast<long>(value);
  }
};

inline constexpr std::string_view kIntegratorChoices[] = {"cvode", "newmark"};
inline constexpr std::string_view kMethodChoices[] = {"bdf", "adams"};
inline constexpr std::string_view kContactChoices[] = {"rigid", "kelvin-voigt"};
inline constexpr std::string_view kLcpChoices[] = {"lemke", "enum"};

// Sized by its rows (std::to_array): a new setting is a row, nothing to count.
inline constexpr auto kSettingFields = std::to_array<SettingField>({
    {"steps", nullptr, &Settings::steps, nullptr,
     "Time-steppers: steps per shortest period N, h = T_min/N (0: default)"},
    {"wh", &Settings::wh, nullptr, nullptr,
     "Time-steppers: the step as w_max h, w_max = 2 pi / T_min (> 0 replaces --steps; 0: use --steps)"},
    {"h_s", &Settings::h_s, nullptr, nullptr,
     "Time-steppers: the step in seconds, the case's time unit (> 0 replaces --steps and --wh)"},
    {"theta", &Settings::theta, nullptr, nullptr, "Moreau-Jean theta"},
    {"gamma", &Settings::gamma, nullptr, nullptr,
     "Faithful time-steppers' activation look-ahead: a contact is in a step when g + gamma h g' <= 0"},
    {"tol_scale", &Settings::tol_scale, nullptr, nullptr, "Event-driven: factor on every internal tolerance"},
    {"step_cap", nullptr, nullptr, &Settings::step_cap, "Most steps or events per run (0: the solver's own cap)"},
    {"time_limit", &Settings::time_limit, nullptr, nullptr,
     "Most wall-clock seconds per run (0: none for `run`; a sweep's points get 60 s each)"},
    {"stiffness", &Settings::stiffness, nullptr, nullptr,
     "Compliant: contact stiffness as the Pi term K, k = K m0 w0^2 (Hertz family: over sqrt(a_p/w_p^2)); 0: default"},
    {"rtol", &Settings::rtol, nullptr, nullptr, "Compliant with cvode: relative tolerance (0: default)"},
    {"integrator", nullptr, nullptr, nullptr, "Compliant: cvode or newmark (default: cvode)", &Settings::integrator,
     kIntegratorChoices},
    {"method", nullptr, nullptr, nullptr, "Compliant with cvode: bdf or adams (default: bdf)", &Settings::method,
     kMethodChoices},
    {"contact", nullptr, nullptr, nullptr,
     "Event-driven: rigid (default) or kelvin-voigt, the compliant solver's Kelvin-Voigt model solved exactly "
     "(with --stiffness)",
     &Settings::contact, kContactChoices},
    {"contact_steps", &Settings::contact_steps, nullptr, nullptr,
     "MuJoCo faithful: the contact time constant 1/w_c in steps, w_c h = 1/M (0: default 2)"},
    {"command", nullptr, nullptr, nullptr,
     "External: the program run per point and its arguments, as words, no shell (docs/external.md)",
     &Settings::command},
    {"name", nullptr, nullptr, nullptr,
     "External: the name its rows' settings and the report give the program (default: its command)", &Settings::name},
    {"lcp", nullptr, nullptr, nullptr,
     "Siconos, a scheme whose variant does not name its LCP solver: lemke or enum (default: lemke)", &Settings::lcp,
     kLcpChoices},
    {"projection_tol", &Settings::projection_tol, nullptr, nullptr,
     "Siconos projections: tolerance on a violated gap, over a_p/w_p^2 (0: default 1e-10)"},
    {"steps_per_sample", nullptr, &Settings::steps_per_sample, nullptr,
     "Time-steppers on a record: the step rule `record`, h = DT/m, m the least whole number >= k with "
     "h <= T_min/N (DT the record's sampling interval; 0: T_min/N alone)"},
});

// The index of a field in kSettingFields by its name, if there is one.
inline std::optional<std::size_t> setting_field_index(std::string_view name) {
  for (std::size_t j = 0; j < kSettingFields.size(); ++j)
    if (kSettingFields[j].name == name) return j;
  return std::nullopt;
}

}  // namespace pb
