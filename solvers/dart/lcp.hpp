#pragma once
// DART's boxed LCP solvers as this project runs them: each counts the solves that did not
// succeed, so that a run can say so, and DART's process-wide state is set up once.
//
// Thread safety (DART 6.12 as Debian builds it, without NDEBUG):
//  - Dantzig's solver (dart::external::ode::dSolveLCP, ODE's) keeps its failure flag on
//    the stack and allocates its work arrays per call; the PGS solver keeps its caches in
//    the solver object, which is the run's own; neither draws random numbers unless
//    asked to randomise the row order (never here).
//  - Both report through dMessage, whose handler is a process-wide pointer: set once
//    (std::call_once) to a handler that counts on the calling thread and prints nothing
//    (DART's own prints to stderr).
//  - ContactConstraint's push-out, softening and bounce threshold are process-wide statics
//    (setErrorReductionParameter, ...): never set here, only read, so the default variant
//    runs DART's compiled-in values.
//  - The world frame does not record its children in 6.12 (Entity::changeParentFrame), so
//    runs that build and destroy skeletons in parallel share nothing.

#include <memory>

#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/constraint/DantzigBoxedLcpSolver.hpp>
#include <dart/constraint/PgsBoxedLcpSolver.hpp>
#include <dart/simulation/World.hpp>

#include "solvers/dart/run_limit.hpp"

namespace pb::dart {

// Sets DART's dMessage handler, once per process.
void prepare_process();

// dMessage calls on this thread so far (Dantzig's "LCP internal error, s <= 0", ...).
long lcp_messages();

class CountingDantzig : public ::dart::constraint::DantzigBoxedLcpSolver {
 public:
  bool solve(int n, double* A, double* x, double* b, int nub, double* lo, double* hi, int* findex,
             bool earlyTermination) override;
  RunLimit* limit = nullptr;  // ticked before each solve (may throw OutOfTime), when set
  // Solves that returned false, or a solution with a NaN (which DART's
  // BoxedLcpConstraintSolver also counts as a failure, and then hands to its fallback).
  long failures = 0;
};

class CountingPgs : public ::dart::constraint::PgsBoxedLcpSolver {
 public:
  bool solve(int n, double* A, double* x, double* b, int nub, double* lo, double* hi, int* findex,
             bool earlyTermination) override;
  RunLimit* limit = nullptr;  // ticked before each solve (may throw OutOfTime), when set
  long calls = 0;     // solves (as DART's fallback: the steps where the primary solver failed)
  long failures = 0;  // solves that stopped at the sweep limit
};

// The LCP solvers of one world, and what they counted.
struct LcpSolvers {
  std::shared_ptr<CountingDantzig> dantzig;  // null where unused
  std::shared_ptr<CountingPgs> pgs;          // null where unused
};

// The faithful variants' constraint solver, set on `world`: Dantzig's, or PGS (`pgs`) with
// `sweeps` sweeps and tolerances 0 (it stops only when a sweep changes nothing: variants.hpp),
// each counting and ticking `limit` before its solves.
LcpSolvers set_faithful_solver(::dart::simulation::World& world, bool pgs, int sweeps, RunLimit& limit);

}  // namespace pb::dart
