#pragma once
// `run`'s settings in physical units: `--k-contact`, a contact element's physical stiffness
// (N/m for a linear element, N/m^1.5 for the Hertz family), turned into the Pi term K that
// --stiffness gives (cases/physical.hpp, stiffness_pi_term) for the solver and variant chosen.

#include <string_view>

#include "cases/case.hpp"
#include "frontend/solver_flags.hpp"
#include "kit/solver.hpp"
#include "studies/physical_settings.hpp"  // hertz_contact

namespace pb::app {

// Sets settings.stiffness to the K of the physical stiffness k; throws BadInput (as
// "--k-contact: why") for a case not in physical units, beside --stiffness, or a k that is
// not finite and > 0. Whether the solver uses it, checked_solver says, as for --stiffness.
void apply_k_contact(const Case& c, std::string_view solver, Settings& settings, double k, bool stiffness_given);

// checked_solver (frontend/solver_flags.hpp) for a run given --k-contact (`k_contact`): the
// K it set counts as --stiffness given, and a complaint about --stiffness names --k-contact,
// the flag the user gave ("--k-contact: not used by moreau-jean ..."; a K the solver refuses
// with its value). Without --k-contact, checked_solver itself.
const SolverInfo& checked_solver_k_contact(const SolverFlags& flags, const GivenSolverFlag& given, bool k_contact);

}  // namespace pb::app
