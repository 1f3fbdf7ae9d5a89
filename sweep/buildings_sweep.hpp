#pragma once
// Solves the points of a buildings case set with one solver (SolverInfo::solve_buildings) on
// several threads, each beside the exact reference's no-contact response of the same point:
// the rows of `spectrum` over a buildings set (rows/buildings_rows.hpp). Every solve is timed
// as the single oscillators' sweeps time theirs (sweep/stopwatch.hpp: the thread's CPU clock,
// the clocks' own cost taken off), so one clock serves every solver and scene.

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "cases/buildings_set.hpp"
#include "kit/solver.hpp"
#include "rows/buildings_rows.hpp"

namespace pb {

// One point: the solver's solve, timed, and the reference's no-contact solve with its free
// watch (buildings::free_motion: the gap that avoids pounding at each contact, and from it
// the point's separation), untimed, which only the limits of `settings` (time_limit, stop) reach.
BuildingsPoint solve_buildings_point(const BuildingScene& scene, const SolverInfo& solver, const Settings& settings);

// Every point, in point order; points are handed out one at a time (a tall pair costs orders of
// magnitude more than a short one). `done(n)` is called after each point, never concurrently.
// Once `cancel` is set no point starts and the running ones are stopped (their settings' stop
// flag): nullopt then.
std::optional<std::vector<BuildingsPoint>> sweep_buildings(std::span<const BuildingCase> points,
                                                           const SolverInfo& solver, const Settings& settings,
                                                           int threads, const std::atomic<bool>& cancel,
                                                           const std::function<void(std::size_t done)>& done);

// How sweep_reference solves each point: with every contact removed and the free watch
// (buildings::free_motion: the gap that avoids pounding at each contact), or as it is
// (buildings::solve).
enum class ReferencePass { free_motion, with_contacts };
// Every point through the exact reference alone (`poundbench separation` over a buildings set),
// points handed out as sweep_buildings does; nullopt once `cancel` is set.
std::optional<std::vector<buildings::BuildingsResult>> sweep_reference(std::span<const BuildingCase> points,
                                                                       ReferencePass pass, int threads,
                                                                       const std::atomic<bool>& cancel,
                                                                       const std::function<void(std::size_t done)>& done);

}  // namespace pb
