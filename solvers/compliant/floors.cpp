#include "solvers/compliant/floors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "kit/run_limits.hpp"
#include "kit/solver.hpp"

namespace pb::compliant {

double building_element_stiffness(const BuildingModel& md, Model model, double K) {
  return contact_element_stiffness(md, model != Model::kelvin_voigt, K);
}

Floors::Floors(const BuildingModel& md, Model model, double K)
    : md_(md),
      slot_(static_cast<std::size_t>(md.n_floors), 0),
      closed_(md.contacts.size(), 0),
      v_minus_(md.contacts.size(), 0.0),
      floor_(kRestitutionFloor * md.speed_scale()) {
  const int n = md.n_floors;
  int tallest = 0;
  for (const Building& b : md.scene.buildings) tallest = std::max(tallest, b.floors());
  for (int level = 1; level <= tallest; ++level)
    for (std::size_t b = 0; b < md.scene.buildings.size(); ++b)
      if (level <= md.scene.buildings[b].floors()) order_.push_back(md.global(static_cast<int>(b), level));
  for (int s = 0; s < n; ++s) slot_[static_cast<std::size_t>(order_[static_cast<std::size_t>(s)])] = s;
  // Rayleigh damping's C has K's tridiagonal pattern (its other entries exactly zero); modal
  // damping's is full within each building.
  start_.push_back(0);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < n; ++c) {
      if (md.K(i, c) == 0.0 && md.C(i, c) == 0.0) continue;
      entries_.push_back({c, md.K(i, c), md.C(i, c)});
      band_ = std::max(band_, std::abs(slot_of(i) - slot_of(c)));
    }
    start_.push_back(static_cast<int>(entries_.size()));
  }
  const double k = building_element_stiffness(md, model, K);
  for (const FloorContact& fc : md.contacts) {
    laws_.push_back(make_law(model, k, md.scene.eps, md.m(fc.i_left), md.m(fc.i_right)));
    band_ = std::max(band_, std::abs(slot_of(fc.i_left) - slot_of(fc.i_right)));
  }
}

void Floors::add_forces(const double* u, const double* v, double* f) const {
  for (int j = 0; j < nc(); ++j) {
    if (!closed(j)) continue;
    const double F = force(j, u, v);
    f[right(j)] += F;
    f[left(j)] -= F;
  }
}

void Floors::close(int j, double q, double t, buildings::FloorPeaks& peaks) {
  if (closed(j)) return;
  closed_[static_cast<std::size_t>(j)] = 1;
  v_minus_[static_cast<std::size_t>(j)] = std::max(q, floor_);
  if (q > 0.0) peaks.impact(static_cast<std::size_t>(j), t, q);
}

const char* Floors::runaway(const double* u, const double* v) const {
  const double bound = 1e6 * md_.length_scale();
  for (int i = 0; i < n(); ++i)
    if (!(std::abs(u[i]) <= bound)) return "|u| above 1e6 a_p/w_p^2";
  if (!(md_.energy(u, v) <= kDivergedEnergy * md_.energy_scale())) return "energy above 1e6 times its scale";
  return nullptr;
}

}  // namespace pb::compliant
