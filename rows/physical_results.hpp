#pragma once
// A row's results in the units of the case (cases/physical.hpp: s, m, kg, N), beside its Pi
// terms: what `run` prints, and the columns, JSON keys and Python keys that carry them. The
// Pi terms stay the spectra's quantities; these answer an engineer's question in metres.
//
//   peak_m             body 0's peak displacement, Pi1 a_p / w_p^2 (m)
//   h_s                a time-stepper's fixed step (s; empty for the reference and CVODE)
//   first_impact_s     the time of the first impact (s; empty: none)
//   impact_velocity    the largest relative approach velocity at an impact (m/s)
//   impact_velocity_pi the same as a Pi term, times w_p / a_p
//   contact_force_max  an element's largest contact force (N, with the case's m0; empty for
//                      rigid contact)
//   penetration_m      the deepest penetration (m; 0 if none)
//
// The lengths are Pi terms times the case's a_p / w_p^2 and the times are the solver's own:
// the units are the case's (m and s when it was given in physical units, or a pulse's a_p
// and w_p in SI), so a row read back gives the same values.

#include <array>
#include <string_view>

#include "rows/row.hpp"

namespace pb {

struct PhysicalResult {
  std::string_view name;  // column and key
  double value;           // NaN: none (an empty field, null in JSON)
};

inline constexpr std::array<std::string_view, 7> kPhysicalResultNames = {
    "peak_m", "h_s", "first_impact_s", "impact_velocity", "impact_velocity_pi", "contact_force_max", "penetration_m"};

std::array<PhysicalResult, 7> physical_results(const Row& row);

// The case's unit of mass: its m0 as given, 1 otherwise (make_system's).
double mass_unit(const Case& c);

}  // namespace pb
