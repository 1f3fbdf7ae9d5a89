#pragma once
// Moreau-Jean on the buildings scene (cases/buildings.hpp): the single oscillators' scheme
// (README.md, "The scheme") with the buildings' M, C and K, which couple the floors of a
// building. The scheme and its choices are in README.md, "Buildings"; in short, per step
// from t_k:
//
//   W_hat   = M + h theta C + h^2 theta^2 K              (factorised once per run)
//   v_free  = v_k + W_hat^-1 h (-(C + h theta K) v_k - K u_k - M 1 abar_k)
//   active  = { j : g_j,k + gamma h g'_j,k <= 0 }       (the floor contacts)
//   0 <= W^T v_k+1 + eps W^T v_k  _|_  P >= 0           on the active contacts
//   v_k+1   = v_free + W_hat^-1 W P,   u_k+1 = u_k + h ((1 - theta) v_k + theta v_k+1)
//
// abar_k is the step's ground load as the single oscillators' (loop_common.hpp: the exact
// step mean, or the end samples of variant end-samples; a record's trapezoids). Peaks are
// read at step ends (FloorPeaks); an impact is a contact that enters the active set
// approaching faster than kRestitutionFloor a_p / w_p.

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/solver.hpp"

namespace pb::moreau_jean {

// Reads steps or wh (h = t_min / N, or w_max h = wh), steps_per_sample on a record, theta,
// gamma, the variant (the load rule), step_cap and time_limit (and stop).
buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings);

}  // namespace pb::moreau_jean
