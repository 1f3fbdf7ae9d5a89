#pragma once
// The exact solution of the compliant solver's Kelvin-Voigt model (solvers/compliant/),
// `event-driven --contact kelvin-voigt --stiffness K`: the reference its integrators are
// measured against, so that integration error and model error (finite stiffness against the
// rigid answer) come apart. DERIVATION.md §8 derives it.
//
// While the set of closed elements is fixed the motion is linear, and the load (a constant
// and the pulse's sinusoid) is itself the solution of a linear system: the state with the
// load appended moves as y(t + h) = exp(A h) y(t), exactly, whatever the damping (critical,
// resonant). Contacts change where a gap crosses zero. Each stretch [t, t + h] is judged by
// the cubic Hermite interpolant of every tracked function (gaps, u0) through its values and
// rates at both ends, whose error is at most max|f''''| h^4 / 384; the fourth derivative is
// bounded mode by mode (each mode's amplitude times its own frequency to the fourth), so a
// stiff element's fast mode, once damped out, no longer shortens the stretch. A stretch that
// is not proven free of a contact change is halved, down to a floor, where the change is.
//
// Rejected: one bound for the whole state (|A|^4 |y|): it charges the bodies' slow motion at
// the contact's frequency, and at K = 1e6 a run took a billion stretches. An eigen
// decomposition for the motion itself: exact, but its coefficients cancel near critical
// damping (eps = 0 makes the element critical) and at resonance, where exp(A h) does not.

#include <string_view>

#include "kit/solver.hpp"

namespace pb::event_driven {

// Settings::contact of the exact compliant reference ("" and "rigid" are the rigid one).
inline constexpr std::string_view kKelvinVoigtContact = "kelvin-voigt";
// The whole state is one matrix (2n + 3 square): above this many bodies a new set of closed
// elements costs more than a CVODE run, and the run says so instead.
inline constexpr int kMaxKelvinVoigtBodies = 24;

Result solve_kelvin_voigt(const System& system, const Settings& settings);

}  // namespace pb::event_driven
