#pragma once
// Bullet Physics (libbullet 3.24, single precision, as Debian ships it) as a pounding
// solver: contacts and restitution are left to Bullet's own constraint solvers; this code
// only builds the bodies, applies the building forces and fills one manifold point per
// active contact in each step.
//
//   bodies    one btRigidBody per building, moving along x only (linear factor (1,0,0),
//             angular factor 0), no gravity, no damping, never deactivated; position u
//             (ground-relative), starting from System::u_start, v_start (empty: at rest).
//             The wall is a static body.
//   forces    -k u - c v - m a_g(t_k) from the state at the start of each step
//             (applyCentralForce); Bullet's step is semi-implicit Euler:
//             v_k+1 = v_k + h F_k / m + (contact impulse) / m, u_k+1 = u_k + h v_k+1:
//             explicit springs, stable only for w h below ~1.9 (README, large steps).
//   contacts  no collision detection: while the variant's activation rule takes contact j
//             at the start of a step (kit/fixed_step.hpp: faithful g + gamma h g' <= 0,
//             si-overlap and default g <= 0), it has one btManifoldPoint (normal +x,
//             distance min(g_j, 0), no friction acting) in its
//             btPersistentManifold, and the manifolds go to the variant's solveGroup
//             (btSequentialImpulseConstraintSolver or btMLCPSolver), which applies Bullet's
//             restitution: target separation speed = restitution x approach speed at the
//             start of the step (setupContactConstraint), with the variant's threshold,
//             ERP, split impulse and warm start.
//   pushed    a contact counts as pushing (StepMonitor, contact phases) when its force
//             over the step is positive.
//
// The run around the steps (h, step count and cap, counts, monitor, history, limits) is
// the shell every time-stepper shares, kit/fixed_step.hpp. Variants and every setting:
// variants.hpp; the engine objects and the step: engine.hpp; modelling, restitution law,
// single precision and what Bullet's defaults change, with numbers:
// solvers/bullet/README.md.

#include <string>

#include "solvers/bullet/variants.hpp"
#include "kit/fixed_step.hpp"
#include "kit/solver.hpp"

namespace pb::bullet {


Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);

// For tests: a configuration given directly (Settings::variant is then ignored).
Result solve_with(const System& system, const Settings& settings, const Config& config);

}  // namespace pb::bullet
