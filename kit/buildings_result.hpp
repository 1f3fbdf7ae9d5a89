#pragma once
// What a solve of the `buildings` scene returns (cases/buildings.hpp): a peak per floor and per
// storey, and per contact its impacts. Every solver of the scene fills it: the exact reference
// (solvers/buildings_reference/) and the time-steppers (SolverInfo::solve_buildings), these
// through FloorPeaks below, which reads their step ends.

#include <limits>
#include <string>
#include <vector>

#include "cases/buildings.hpp"
#include "kit/solver.hpp"

namespace pb::buildings {

struct ContactResult {
  int left = 0, right = 0;  // buildings, numbered from 0
  int floor = 1;            // numbered from 1
  long impacts = 0;         // closures approaching faster than the plastic speed
  long contact_phases = 0;  // entries into persistent contact (the reference; 0 for a time-stepper)
  // The largest approach speed -g' at an impact (m/s), and the first impact's time (s); NaN
  // where there is none.
  double impact_velocity_max = std::numeric_limits<double>::quiet_NaN();
  double first_impact = std::numeric_limits<double>::quiet_NaN();
  // The free watch (the reference's free_motion, every contact removed): how far the two
  // floors come towards each other, max(u_left - u_right), and how far apart,
  // max(u_right - u_left), over [0, t_end] (m). The first is the gap that avoids pounding at
  // this level; the second, for linear buildings, that under the load reversed. NaN elsewhere.
  double closing = std::numeric_limits<double>::quiet_NaN();
  double opening = std::numeric_limits<double>::quiet_NaN();
};

// The energy terms at t_end (J): the ground load's work equals what the floors hold plus what
// the dampers and the impacts (and the merging of floors that stick) took.
struct Energies {
  double input = 0.0, kinetic = 0.0, elastic = 0.0, damped = 0.0, impacts = 0.0;
};

struct BuildingsResult {
  Status status = Status::ok;
  std::string message;
  // Per building (left to right), per floor (floor 1 first): the peak |u_i| over
  // [0, t_end] (m) and where it is (s); per storey the peak |u_i - u_{i-1}| likewise. A
  // time-stepper's peaks are over its step ends.
  std::vector<std::vector<double>> floor_peak, floor_peak_time;
  std::vector<std::vector<double>> drift_peak, drift_peak_time;
  std::vector<ContactResult> contacts;  // as BuildingModel::contacts
  long events = 0;  // the reference's events; a time-stepper's steps
  Energies energies;
  // The largest |input - (kinetic + elastic + damped + impacts)| over the run's events, over
  // max(BuildingModel::energy_scale(), |input|): round-off for the exact motion; NaN where a
  // solver does not measure it.
  double energy_error = std::numeric_limits<double>::quiet_NaN();
  double min_gap = std::numeric_limits<double>::infinity();  // the most negative gap at an event or step end (m)
  double t_end = 0.0;
  double step = std::numeric_limits<double>::quiet_NaN();  // a time-stepper's fixed h (s)
};

// A run that failed before it had an answer, and why (h: the step it would have taken).
BuildingsResult failed(std::string why, double h = std::numeric_limits<double>::quiet_NaN());

// A time-stepper's steps on the scene, as the single oscillators' (kit/fixed_step.hpp,
// plan_steps): h = t_min / N (BuildingModel::t_min; N = settings.steps, else default_steps),
// or w_max h = settings.wh, or a record's step rule (settings.steps_per_sample); n the steps to
// t_end. Sets r's step and t_end; false, with r's status and message, where the run cannot
// start: a step not usable for t_end, longer than the pulse period (step_problem's bound), the
// rule without a record, or more steps than the cap (settings.step_cap, else kDefaultStepCap).
bool plan_steps(const BuildingModel& model, const Settings& settings, int default_steps, BuildingsResult& r, long& n);

// The peaks of a motion sampled at step ends, for a time-stepper: sample() after every step
// (no allocation), impact() where the solver's contact law says a contact closed, and into()
// at the end. Floors are the model's global indices.
class FloorPeaks {
 public:
  explicit FloorPeaks(const BuildingModel& model);
  // The floors' displacements u (model.n_floors of them) at time t.
  void sample(double t, const double* u);
  // Contact c (as BuildingModel::contacts) closed at time t approaching at speed -g' > 0.
  void impact(std::size_t c, double t, double approach_speed);
  // Writes the peaks, the contacts and min_gap into r (its other fields are the solver's).
  void into(BuildingsResult& r) const;

 private:
  const BuildingModel& model_;
  std::vector<double> floor_, floor_t_, drift_, drift_t_;  // per global floor
  std::vector<char> ground_below_;                         // per global floor: a building's floor 1
  std::vector<ContactResult> contacts_;
  double min_gap_ = std::numeric_limits<double>::infinity();
};

}  // namespace pb::buildings
