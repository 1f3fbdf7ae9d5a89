#pragma once
// Compliant contact, as earthquake engineers model pounding: a contact element (a spring,
// or a spring and a dashpot) acts between neighbours while their gap is closed
// (contact_law.hpp), and the motion is an ordinary differential equation, integrated by
//
//   cvode    SUNDIALS CVODE (BDF or Adams, variable order and step, error-controlled at
//            --rtol), with root functions on every gap (the element starts and ends exactly
//            there, and CVODE restarts, as the force may jump) and on body 0's velocity (the
//            extremum of u0, so Pi1 is read at its root, not at a step). Pi1 = max |u0| over
//            those roots, the steps' ends and the run's ends. A yielding body's branch is a
//            mode, switched at roots on yield and on unloading (cvode_run.cpp).
//   newmark  average-acceleration Newmark (gamma 1/2, beta 1/4) at the fixed step
//            h = T_min / N, with Newton iterations on the contact forces: what OpenSees runs
//            by default (`integrator Newmark 0.5 0.25`, `algorithm Newton`). The contact's
//            own period is not in T_min: a step that does not resolve it shows as
//            penetration, restitution and energy in the row, and a Newton iteration that
//            does not converge ends the run with status failed and says where. A step is
//            split where the load jumps and where an element opens or closes (second order
//            across each: newmark.cpp); Pi1 is read at the steps' ends k h only.
//
// The variant is the element (kelvin-voigt, the default; hertz; hunt-crossley; jankowski;
// jankowski-published, his element with his own zeta(eps));
// --stiffness is its Pi term K (default kDefaultStiffness). Both integrators load the
// bodies with -m a_g(t) at the times they evaluate (CVODE: every stage; Newmark: the step
// ends, as its trapezoidal rule asks).
//
// Counts: impacts are contact onsets while approaching; contact_phases stays 0 (a compliant
// contact has no persistent phase of its own). Restitution is measured per isolated contact
// (the only one closed from its onset to its end, approaching faster than the floor) as
// -q(end) / q(onset). CVODE reports no energy balance (NaN); Newmark's runs through the
// shell's monitor, which counts no energy stored in the elements (so a contact in progress
// lowers the balance, never raises it).

#include <optional>
#include <string>
#include <vector>

#include "kit/solver.hpp"

namespace pb::compliant {

inline constexpr double kDefaultRtol = 1e-8;
inline constexpr long kDefaultCvodeStepCap = 10'000'000;

Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);
std::vector<VariantInfo> variant_list();
// The reference of a setting's model: for Kelvin-Voigt the exact one (event-driven --contact
// kelvin-voigt at the same stiffness); for the Hertz family, CVODE at rtol kModelReferenceRtol
// (BDF), which no other setting of it is (nullopt for that one itself).
std::optional<ModelReference> model_reference(const Settings& settings);
// Whether the variant's element is of the Hertz family (every model but kelvin-voigt):
// SolverInfo::hertz_contact.
bool hertz_contact(const Settings& settings);
// CVODE's tolerance as the Hertz family's reference: measured on the Kelvin-Voigt element
// against its exact solution, within 1.7e-9 over the smoke set (compliant_test.cpp).
inline constexpr double kModelReferenceRtol = 1e-12;

}  // namespace pb::compliant
