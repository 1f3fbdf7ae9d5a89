#pragma once
// A settings list's [[run]] in physical units (issue 35): the step `h_s` in seconds and the
// contact stiffness `k_contact` in N/m (N/m^1.5 for the Hertz family), instead of the Pi
// forms steps / wh and stiffness, never beside them in one [[run]]. Both hold across the cases
// of a study (issue 51: three records of one pair of buildings): the step is the solvers' own
// (Settings::h_s), each case's N following from it, and each case takes its own Pi term K of
// the stiffness (Settings::k_contact; sweep/sweep.hpp, run_point; cases/physical.hpp,
// stiffness_pi_term), its unit of mass the case's m0.

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

// Sets Settings::h_s and Settings::k_contact of every list run given in physical units; throws
// SettingsListError ("SOURCE: run R (solver settings): k_contact: why") when a case is not in
// physical units (k_contact: its unit of mass is m0's), or when the solver's check refuses them.
void resolve_physical_settings(SettingsList& list, std::span<const Case> cases, std::string_view source);

}  // namespace pb
