#pragma once
// Simbody on the buildings scene (cases/buildings.hpp; solvers/simbody/README.md, "Buildings"):
// a MobilizedBody::Slider along x from the ground per floor, all at the ground's origin; each
// storey a Force::TwoPointLinearSpring between the floor and the one below it (floor 1: the
// ground); the building's damping C carried by Simbody's elements where they can carry it
// (Rayleigh: C = a0 M + a1 K, a MobilityLinearDamper a0 m_i on each floor's slider and a
// TwoPointLinearDamper a1 k_i beside each storey's spring), else by a Force::Custom applying
// -(C v) whole (modal C, which couples every floor); the ground load -m_i a_g(t) a Force::Custom;
// a PointPlaneFrictionlessContact per floor contact. Stepped by SemiExplicitEulerTimeStepper,
// the single oscillators' stepper variants: plus-faithful and pgs-faithful (Poisson's law with
// eps, the predicted rule g + gamma h g' <= 0, no projection) and default (its own margin and
// projection); hunt-crossley is refused by name. All in the pulse's units, masses over floor 1's
// of building 0. Peaks at every step end (FloorPeaks); an impact is a contact that enters the
// stepper's proximal set approaching faster than kRestitutionFloor a_p / w_p at the step's start.

#include <string_view>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/solver.hpp"

namespace pb::simbody {

// The settings the buildings solve reads (SolverInfo::buildings_settings), besides the variant.
inline constexpr std::string_view kBuildingsSettings[] = {"steps", "wh", "h_s", "steps_per_sample", "gamma", "step_cap",
                                                          "time_limit"};

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings);

}  // namespace pb::simbody
