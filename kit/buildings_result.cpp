#include "kit/buildings_result.hpp"

#include <cmath>
#include <numbers>

#include "cases/record.hpp"
#include "cases/text.hpp"
#include "kit/fixed_step.hpp"

namespace pb::buildings {

BuildingsResult failed(std::string why, double h) {
  BuildingsResult r;
  r.status = Status::failed;
  r.message = std::move(why);
  r.step = h;
  return r;
}

namespace {

// The step, and in `why` the reason it cannot be taken ("" when it can).
double fixed_step(const BuildingModel& model, const Settings& settings, int default_steps, std::string& why) {
  double h = settings.h_s > 0.0  ? settings.h_s
             : settings.wh > 0.0 ? settings.wh * model.t_min / (2.0 * std::numbers::pi)
                                 : model.t_min / (settings.steps > 0 ? settings.steps : default_steps);
  const auto& record = model.scene.pulse.record;
  if (settings.steps_per_sample > 0) {
    if (!record) {
      why = "steps_per_sample: the step rule `record` needs a record's samples, and this case's load is a pulse "
            "(its step is T_min / N: leave it out)";
      return h;
    }
    h = record_step(*record, h, settings.steps_per_sample);
  }
  if (!(h > 0.0) || !std::isfinite(h) || !(model.t_end / h < 1e18)) {
    why = "step: h = " + format_number(h) + " is not a usable step for t_end = " + format_number(model.t_end);
    return h;
  }
  System pulse_only;  // step_problem reads the pulse's period alone
  pulse_only.pulse = model.scene.pulse;
  why = step_problem(pulse_only, h);
  return h;
}

}  // namespace

bool plan_steps(const BuildingModel& model, const Settings& settings, int default_steps, BuildingsResult& r, long& n) {
  std::string why;
  const double h = fixed_step(model, settings, default_steps, why);
  r.step = h;
  r.t_end = model.t_end;
  if (!why.empty()) {
    r.status = Status::failed;
    r.message = std::move(why);
    return false;
  }
  n = step_count(model.t_end, h);
  const long cap = settings.step_cap > 0 ? settings.step_cap : kDefaultStepCap;
  if (n <= cap) return true;
  r.status = Status::step_cap;
  r.message = "the run needs " + std::to_string(n) + " steps, more than the cap " + std::to_string(cap);
  return false;
}

FloorPeaks::FloorPeaks(const BuildingModel& model)
    : model_(model),
      floor_(static_cast<std::size_t>(model.n_floors), 0.0),
      floor_t_(floor_.size(), 0.0),
      drift_(floor_.size(), 0.0),
      drift_t_(floor_.size(), 0.0),
      ground_below_(floor_.size(), 0) {
  // Floor 1 of a building stands on the ground (u_0 = 0): its storey's drift is u itself.
  for (int f : model.first) ground_below_[static_cast<std::size_t>(f)] = 1;
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
    const double x = std::abs(u[i]);
    const double d = std::abs(ground_below_[k] ? u[i] : u[i] - u[i - 1]);
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
