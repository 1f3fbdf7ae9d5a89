#pragma once
// The Open Dynamics Engine (ODE 0.16, Debian's libode) as a pounding solver: contacts and
// restitution are left to ODE's own constraint solver; this code only builds the scene,
// applies the building forces and makes the contact joints of each step.
//
//   bodies    one dBody per building on the x axis, position = u (ground-relative), starting
//             from System::u_start, v_start (empty: at rest), no gravity, no auto-disable; y, z and rotation stay exactly zero because every
//             force and every contact Jacobian has only an x component (checked at the
//             end of each run).
//   forces    -k u - c v - m a_g(t) at the start of each step (dBodyAddForce); ODE then
//             steps v += h/m (F + contact force), u += h v_new (semi-implicit Euler):
//             explicit springs, stable only for w h below ~1.9 (README, large steps).
//   contacts  no collision detection: for each contact of the scene that the variant's
//             activation rule takes (kit/fixed_step.hpp: faithful g + gamma h g' <= 0,
//             default g <= 0) a dContactJoint with normal +x on the right
//             body (the wall is the static environment), depth max(0, -g), mu 0, and
//             dContactBounce with bounce = eps: ODE's Newton-type law, target separation
//             speed eps times the approach speed at the start of the step.
//   pushed    a contact counts as pushing (StepMonitor, contact phases) when its force
//             over the step is positive.
//
// The run around the steps (h, step count and cap, counts, monitor, history, limits) is
// the shell every time-stepper shares, kit/fixed_step.hpp. The modelling, the settings
// of each variant and what ODE's defaults change are in solvers/ode/README.md; the engine
// set-up and its thread safety in world.hpp.

#include <string>

#include "solvers/ode/variants.hpp"
#include "kit/fixed_step.hpp"
#include "kit/solver.hpp"

namespace pb::ode {


Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);

// For tests: a configuration other than the named variants (Settings::variant is then
// ignored).
Result solve_with(const System& system, const Settings& settings, const Config& config);

}  // namespace pb::ode
