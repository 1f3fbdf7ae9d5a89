#pragma once
// A settings list's [[run]] in physical units (issue 35): the step `h_s` in seconds and the
// contact stiffness `k_contact` in N/m (N/m^1.5 for the Hertz family), instead of the Pi
// forms steps / wh and stiffness, never beside them in one [[run]]. They are mapped to the
// Pi forms per case, as `run --k-contact` maps its stiffness, by the conversions of
// cases/physical.hpp: w_max h = step_pi_term(system, h_s) = 2 pi h_s / T_min and
// K = stiffness_pi_term(case, k_contact). A study runs one setting over
// every case, so the cases of a study must map them to one value each: one case (a study
// of the case given by flags), or cases of one set of buildings (the self-similar twins).

#include <span>
#include <string_view>

#include "cases/case.hpp"
#include "kit/solver.hpp"

namespace pb {

struct SettingsList;

// The physical values a [[run]] setting was given; 0: not given (a Pi form, or the default).
struct PhysicalSetting {
  double h_s = 0;        // the fixed step (s)
  double k_contact = 0;  // the contact stiffness (N/m; N/m^1.5 for the Hertz family)
  bool given() const { return h_s > 0.0 || k_contact > 0.0; }
};

// Whether the solver's contact element with these settings is of the Hertz family (force
// k p^1.5): as its registry row says (SolverInfo::hertz_contact).
inline bool hertz_contact(const SolverInfo& solver, const Settings& settings) {
  return solver.hertz_contact && solver.hertz_contact(settings);
}

// Sets the Pi forms (wh, stiffness) of every list run given in physical units from the
// cases; throws SettingsListError ("SOURCE: run R (solver settings): h_s: why") when a case
// is not in physical units (k_contact: its unit of mass is m0's), when the cases map a
// value to different Pi forms, or when the solver's check refuses what it maps to.
void resolve_physical_settings(SettingsList& list, std::span<const Case> cases, std::string_view source);

}  // namespace pb
