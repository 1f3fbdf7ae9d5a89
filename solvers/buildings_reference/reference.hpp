#pragma once
// The exact reference of the `buildings` scene: two or three shear buildings in a row,
// pounding floor against floor (cases/buildings.hpp). Between events every floor's motion is
// a closed form (modal superposition of the buildings, or of the stuck system's complex
// modes where floors move together); closures, releases and the load's breakpoints are
// events located to an ulp; impacts follow Newton's law over every closed contact, and the
// acceleration LCP decides which floors stick. DERIVATION.md derives each piece.
//
// It returns plain data and prints nothing, as every solver does; it is not in the registry
// (the scene has its own result: a peak per floor and per storey, and per contact its impacts).

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
  long contact_phases = 0;  // entries into persistent contact
  // The largest approach speed -g' at an impact (m/s), and the first impact's time (s); NaN
  // where there is none.
  double impact_velocity_max = std::numeric_limits<double>::quiet_NaN();
  double first_impact = std::numeric_limits<double>::quiet_NaN();
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
  // [0, t_end] (m) and where it is (s); per storey the peak |u_i - u_{i-1}| likewise.
  std::vector<std::vector<double>> floor_peak, floor_peak_time;
  std::vector<std::vector<double>> drift_peak, drift_peak_time;
  std::vector<ContactResult> contacts;  // as BuildingModel::contacts
  long events = 0;
  Energies energies;
  // The largest |input - (kinetic + elastic + damped + impacts)| over the run's events, over
  // max(BuildingModel::energy_scale(), |input|): round-off for the exact motion.
  double energy_error = std::numeric_limits<double>::quiet_NaN();
  double min_gap = std::numeric_limits<double>::infinity();  // the most negative gap at an event (m)
  double t_end = 0.0;
};

// A run is ok only if its energy balance holds within this (times tol_scale above 1) and no gap
// went below ten closure tolerances.
inline constexpr double kEnergyCheck = 1e-9;

// Settings read: tol_scale, step_cap (events), time_limit and stop. A scene that does not
// validate fails with validate()'s reason.
BuildingsResult solve(const BuildingScene& scene, const Settings& settings = {});
BuildingsResult solve(const BuildingModel& model, const Settings& settings = {});

}  // namespace pb::buildings
