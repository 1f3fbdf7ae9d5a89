#include "rows/physical_results.hpp"

#include <cmath>

#include "cases/physical.hpp"

namespace pb {

double mass_unit(const Case& c) { return std::isnan(c.physical.m0) ? 1.0 : c.physical.m0; }

std::array<PhysicalResult, 7> physical_results(const Row& row) {
  const Case& c = row.input;
  const Result& r = row.result;
  const double length = c.a_p / (c.w_p * c.w_p);
  return {{
      {kPhysicalResultNames[0], r.pi1 * length},
      {kPhysicalResultNames[1], r.step},
      {kPhysicalResultNames[2], r.first_impact},
      {kPhysicalResultNames[3], r.impact_velocity_max},
      {kPhysicalResultNames[4], velocity_pi_term(c, r.impact_velocity_max)},
      {kPhysicalResultNames[5], r.contact_force_max * mass_unit(c)},
      {kPhysicalResultNames[6], penetration(row) * length},
  }};
}

}  // namespace pb
