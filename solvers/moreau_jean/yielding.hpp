#pragma once
// Moreau-Jean with yielding bodies (cases/README.md, "Yielding"): the yield law is a second
// nonsmooth law in the same step, as Moreau wrote plasticity, a sweeping process
// z' in u' - N_[-u_y, u_y](z). Its implicit (catching-up) step is the return map
//
//   z_k+1 = clamp(z_k + (q_k+1 - q_k), -u_y, u_y),   r_k+1 = alpha k q_k+1 + (1 - alpha) k z_k+1,
//
// taken at the step's end together with Newton's impact law, and the theta-method weights
// r_k+1 and r_k as it weights k q_k+1 and k q_k on an elastic body. r_k+1 is linear in
// q_k+1 on each branch (elastic: k q_k+1 - (1 - alpha) k (q_k - z_k); yielding at
// z = s u_y: alpha k q_k+1 + (1 - alpha) k s u_y), so a step with given branches is the
// elastic step with another stiffness and a constant force; the step's branches are found
// by an active-set iteration (semismooth Newton on the monotone piecewise-linear step
// equation): the last step's branches first, then each body's branch where its return map
// put it, until none changes (README.md, "Yielding").
//
// Any row of bodies takes this loop (the any-size one of dynamic.hpp, whose contact
// solution it shares); a system without a yielding body never reaches it.

#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb::moreau_jean {

// The run of a yielding system with step h, n steps, its step plan's Result res.
Result run_yielding(const System& sys, const Settings& set, double h, long n, Result res);

}  // namespace pb::moreau_jean
