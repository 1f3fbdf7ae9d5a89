#pragma once
// Siconos on the buildings scene (cases/buildings.hpp): one LagrangianLinearTIDS per building
// with its full M (diagonal), K and C, one Interaction per floor pair (LagrangianLinearTIR
// y = delta + u_right - u_left over the two buildings, NewtonImpactNSL(eps)), TimeStepping
// with MoreauJeanOSI(theta, gamma), h = t_min / N (or w_max h = wh) as moreau-jean's. The
// ground load F_ext = -M 1 a_g(t) is a plugin sampled at the step ends (Pulse::sample, a
// record's LoadCursor): MoreauJeanOSI weights those samples by theta, as moreau-jean's
// variant end-samples does, so the two are the same scheme and agree to round-off
// (buildings_test.cpp). Siconos sees the scene in the pulse's units, as the single
// oscillators (model.hpp). Peaks at every step end (FloorPeaks); an impact is a contact that
// enters Siconos' index set approaching faster than kRestitutionFloor a_p / w_p, as
// moreau-jean counts them. Variants: moreau-jean-lemke and moreau-jean-enum (the latter up
// to kMaxEnumerationContacts contacts); the others are refused by name.

#include <string_view>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/solver.hpp"

namespace pb::siconos {

// The settings the buildings solve reads (SolverInfo::buildings_settings), besides the variant.
inline constexpr std::string_view kBuildingsSettings[] = {"steps", "wh", "h_s",         "steps_per_sample", "theta",
                                                          "gamma", "step_cap",   "time_limit"};

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings);

}  // namespace pb::siconos
