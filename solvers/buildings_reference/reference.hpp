#pragma once
// The exact reference of the `buildings` scene: two or three shear buildings in a row,
// pounding floor against floor (cases/buildings.hpp). Between events every floor's motion is
// a closed form (modal superposition of the buildings, or of the stuck system's complex
// modes where floors move together); closures, releases and the load's breakpoints are
// events located to an ulp; impacts follow Newton's law over every closed contact, and the
// acceleration LCP decides which floors stick. DERIVATION.md derives each piece.
//
// It returns plain data (kit/buildings_result.hpp) and prints nothing, as every solver does;
// the registry's reference row names it as its buildings solve.

#include <limits>
#include <string>
#include <vector>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/solver.hpp"

namespace pb::buildings {

// A run is ok only if its energy balance holds within this (times tol_scale above 1) and no gap
// went below ten closure tolerances.
inline constexpr double kEnergyCheck = 1e-9;

// Settings read: tol_scale, step_cap (events), time_limit and stop. A scene that does not
// validate fails with validate()'s reason.
BuildingsResult solve(const BuildingScene& scene, const Settings& settings = {});
BuildingsResult solve(const BuildingModel& model, const Settings& settings = {});

// The motion with every contact removed, watched at the floor pairs the scene's contacts join
// (every floor both neighbours have, or the floors named; whatever scene.no_contact says): the
// no-contact response solve() gives (its peaks, events and energy balance), with its contacts
// listed, none impacting, each with the free watch (ContactResult::closing, opening): the
// largest u_left - u_right and u_right - u_left over [0, t_end], by the certified search of
// their closed forms (max_both), not from samples.
BuildingsResult free_motion(const BuildingScene& scene, const Settings& settings = {});

}  // namespace pb::buildings
