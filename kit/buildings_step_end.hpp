#pragma once
// The end of a time-stepper's step on the buildings scene, as every engine's loop ends one
// (solvers/<engine>/buildings.cpp): the floors' state checked, sampled into the peaks, and the
// deadline looked at, with one wording of why a run stopped.

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/run_limits.hpp"

namespace pb::buildings {

// After step k (counted from 0) of n steps of h, the floors at u, v (BuildingModel::n_floors
// each, m and m/s): a state that is not finite ends the run as nan, a floor beyond
// 1e6 a_p / w_p^2 as diverged, each "... at step K (t = T)" with K = k + 1; else the state is
// sampled into peaks and, where another step follows and `deadline` is given, a passed deadline
// ends it as time_limit. Returns false, with r's status and message, where the run ends: it has
// taken k + 1 steps.
bool end_step(const BuildingModel& model, long k, long n, double h, const double* u, const double* v,
              FloorPeaks& peaks, Deadline* deadline, BuildingsResult& r);

}  // namespace pb::buildings
