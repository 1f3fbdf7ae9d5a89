#include "kit/buildings_result.hpp"

#include <cmath>

namespace pb::buildings {

FloorPeaks::FloorPeaks(const BuildingModel& model)
    : model_(model),
      floor_(static_cast<std::size_t>(model.n_floors), 0.0),
      floor_t_(floor_.size(), 0.0),
      drift_(floor_.size(), 0.0),
      drift_t_(floor_.size(), 0.0) {
  for (const FloorContact& fc : model.contacts) {
    ContactResult c;
    c.left = fc.left;
    c.right = fc.right;
    c.floor = fc.floor;
    contacts_.push_back(c);
  }
}

void FloorPeaks::sample(double t, const double* u) {
  for (int i = 0; i < model_.n_floors; ++i) {
    const auto k = static_cast<std::size_t>(i);
    // Floor 1 of a building stands on the ground (u_0 = 0).
    const bool ground_below = model_.first[static_cast<std::size_t>(model_.building_of[k])] == i;
    const double x = std::abs(u[i]);
    const double d = std::abs(ground_below ? u[i] : u[i] - u[i - 1]);
    if (x > floor_[k]) floor_[k] = x, floor_t_[k] = t;
    if (d > drift_[k]) drift_[k] = d, drift_t_[k] = t;
  }
  for (const FloorContact& fc : model_.contacts)
    min_gap_ = std::min(min_gap_, model_.scene.delta + u[fc.i_right] - u[fc.i_left]);
}

void FloorPeaks::impact(std::size_t c, double t, double approach_speed) {
  ContactResult& r = contacts_[c];
  ++r.impacts;
  if (!(r.first_impact <= t)) r.first_impact = t;
  if (!(r.impact_velocity_max >= approach_speed)) r.impact_velocity_max = approach_speed;
}

void FloorPeaks::into(BuildingsResult& r) const {
  const std::size_t nb = model_.first.size();
  r.floor_peak.assign(nb, {});
  r.floor_peak_time.assign(nb, {});
  r.drift_peak.assign(nb, {});
  r.drift_peak_time.assign(nb, {});
  for (int i = 0; i < model_.n_floors; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const auto b = static_cast<std::size_t>(model_.building_of[k]);
    r.floor_peak[b].push_back(floor_[k]);
    r.floor_peak_time[b].push_back(floor_t_[k]);
    r.drift_peak[b].push_back(drift_[k]);
    r.drift_peak_time[b].push_back(drift_t_[k]);
  }
  r.contacts = contacts_;
  r.min_gap = min_gap_;
}

}  // namespace pb::buildings
