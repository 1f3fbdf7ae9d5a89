#pragma once
// MuJoCo (Debian's libmujoco 2.2.2) as a pounding solver: a soft-contact engine. Its
// contacts are spring-dampers solved by its constraint solver, with no coefficient of
// restitution; the faithful variants calibrate each one to eps (contact.hpp), the default
// variant keeps MuJoCo's own contact parameters.
//
//   model     model.hpp: slide joints with MuJoCo's own joint stiffness and damping,
//             spheres and a wall plane whose distances are the gaps, one explicit condim-1
//             pair per contact, the ground load from mjcb_control at every evaluation.
//   step      mj_step with the variant's integrator, h = T_min / N (or --wh).
//   contacts  MuJoCo's collision decides when a contact exists: at overlap, g < 0, found at
//             each evaluation (once per step, or at each RK4 stage). The shared activation
//             rule of the faithful rigid-contact time-steppers (fixed_step.hpp) does not
//             apply: a soft contact has no Newton law to impose ahead of time.
//   counts    impacts are contacts that close while approaching; contact_phases stay 0 (a
//             soft contact has no persistent phase of its own); restitution is measured
//             over whole contacts, -g'(end) / g'(onset), for the isolated ones (the only
//             contact closed from its onset to its end, approaching faster than the floor).
//
// The run around the steps (h, step count and cap, monitor, history, limits) is the shell
// every time-stepper shares, kit/fixed_step.hpp. Calibration, pitfalls and
// measurements: solvers/mujoco/README.md.

#include <string>

#include "solvers/mujoco/variants.hpp"
#include "kit/solver.hpp"

namespace pb::mujoco {

Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);

}  // namespace pb::mujoco
