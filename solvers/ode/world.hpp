#pragma once
// ODE's process and thread set-up, and the engine objects of one run.
//
// Thread safety (ODE 0.16.2 as Debian builds it: "ODE_EXT_threading ODE_THR_builtin_impl
// ODE_double_precision", without ODE_EXT_mt_collisions):
//  - dInitODE2 runs once per process (std::call_once) and dAllocateODEDataForThread once
//    per thread that steps a world (a thread_local flag). The library is initialised
//    without dInitFlagManualThreadCleanup, so ODE frees a thread's data itself.
//  - Every world gets its own self-threaded threading implementation: a world without
//    one shares a process-wide default whose job list uses no locks, which ODE's own
//    header says is unsafe when worlds step in parallel threads.
//  - Collision detection is what ODE_EXT_mt_collisions would make thread-safe; this solver
//    never calls it (the contacts are made by hand), so its absence does not matter.
//  - dWorldQuickStep reorders the rows of a step with two or more constraints every
//    eighth sweep with dRandInt, from one process-wide seed. Left alone, a row3 run would
//    depend on every run before it in the process and on other threads (measured: Pi1
//    moves by 1e-4 relative on a double-contact row3 case, because round-off differences
//    flip later contact decisions). quick_step() therefore resets the seed before every
//    such step, under a process-wide lock, so a step is a function of its state only.
//    Steps with fewer than two rows draw nothing and take no lock; dantzig draws nothing.

#include <ode/ode.h>

#include <string>

#include "solvers/ode/variants.hpp"

namespace pb::ode {

// Initialises ODE for the process (once) and the calling thread (once per thread).
// Returns false when ODE refuses either.
bool prepare_thread();

// dMessage output of ODE on this thread since the last call (ODE's warnings, such as an
// LCP that failed to converge); the text is kept, never printed.
std::string take_messages();

// How many times ODE's Dantzig LCP gave up (d_ERR_LCP, "LCP internal error, s <= 0") on
// this thread so far. It then zeroes the forces of every row it had not reached, so the
// step that reported it is wrong (solvers/ode/README.md, degenerate LCPs).
long lcp_failures();

// dWorldQuickStep, with ODE's random row order made reproducible when it is used
// (rows >= 2): the seed is reset to the same value first, under a lock.
int quick_step(dWorldID world, double h, int rows);

// One world, its own threading implementation and the joint group of the contacts of a
// step. Not copyable; destroys everything it made.
class World {
 public:
  World();
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  bool ok() const { return world_ != nullptr && contacts_ != nullptr; }
  dWorldID id() const { return world_; }
  dJointGroupID contacts() const { return contacts_; }

 private:
  dThreadingImplementationID threading_ = nullptr;
  dWorldID world_ = nullptr;
  dJointGroupID contacts_ = nullptr;
};

// A world as a variant runs it (variants.hpp): no gravity, the variant's ERP, CFM, push-out cap
// and surface layer, no sleeping, no world damping, and quickstep's sweeps and SOR.
void configure_world(dWorldID world, const Config& config);

}  // namespace pb::ode
