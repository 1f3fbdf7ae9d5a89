#pragma once
// The compliant solver on the buildings scene (cases/buildings.hpp): a contact element at every
// floor pair of BuildingModel::contacts, as engineers model pounding floor by floor in
// OpenSees (zeroLength elements with an impact material), integrated as the single oscillators
// are (compliant.hpp):
//
//   cvode    SUNDIALS CVODE on the first-order system (BDF or Adams, --rtol), a root function
//            per gap (each element starts and ends there, and CVODE restarts), per floor's
//            velocity and per upper storey's drift rate (each floor's and storey's peak is read
//            at its extremum, not at a step); the run is cut where the load has a breakpoint.
//   newmark  average-acceleration Newmark at the fixed step h = t_min / N (--steps, --wh), with
//            Newton's iteration on the contact forces, each step split where the load jumps and
//            where an element opens or closes; the peaks are read at the steps' ends k h.
//
// The variant is the element (kit/contact_elements/contact_law.hpp; the hertz element takes
// eps = 1 only, the other Hertz-type ones eps > 0, as on the single oscillators); --stiffness
// is the Pi term K, whose unit for buildings floors.hpp states (cases/README.md, "Buildings").
// Impacts: one per closure while approaching (a whole contact, from closure to opening), at
// the approach speed at closure; min_gap is the most negative gap seen (the deepest
// penetration at the samples: CVODE's returns, Newmark's step ends). `events` counts CVODE's
// internal steps or Newmark's steps; the energy balance is not measured (NaN).

#include <string_view>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/contact_elements/contact_law.hpp"
#include "kit/solver.hpp"

namespace pb::compliant {

// The settings the buildings solve reads (SolverInfo::buildings_settings), besides the variant;
// any other given is refused.
inline constexpr std::string_view kBuildingsSettings[] = {"stiffness", "rtol",     "integrator", "method",
                                                          "steps",     "wh", "h_s",       "step_cap",   "time_limit"};

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings);

// The two integrators (buildings_cvode.cpp, buildings_newmark.cpp), the settings checked.
buildings::BuildingsResult run_buildings_cvode(const BuildingModel& model, const Settings& settings, Model element,
                                               double K, bool adams);
buildings::BuildingsResult run_buildings_newmark(const BuildingModel& model, const Settings& settings, Model element,
                                                 double K);

}  // namespace pb::compliant
