#pragma once
// The run's time limit (and a sweep's stop flag) inside DART, where the shared step loop's
// look between steps comes too late (issue 46). Measured on a chain of 1000 touching bodies
// (dantzig-faithful, a loaded 2-core machine) with a limit of 1 s: 110 s. Adding the bodies
// to the faithful model's one skeleton took 35-40 s of CPU (a skeleton per building since:
// gap_constraint.hpp), then a step 0.6-0.8 s of CPU, half of it the BoxedLcpConstraintSolver's
// matrix (one unit impulse per contact row, each then O(bodies)) and half Dantzig's LCP on its
// 999 rows; now a step is 0.5-0.8 s of wall, 0.4-0.57 s of it the LCP.
//
// A RunLimit is one Deadline started before the model is built, and this folder's own code
// ticks it wherever DART calls it or is called: each body added, each step, each unit impulse
// of a GapConstraint (DART asks one per row while it fills the LCP's matrix), each LCP solve
// before it starts. Past the limit it throws OutOfTime, which the builder and the engines
// catch around World::step: DART unwinds through its own C++ (the constraint solver keeps its
// work arrays in members), the run ends time-limit at the step's start, and the world is
// destroyed unused. What it cannot cut is one LCP solve once started: Dantzig's on 999 rows
// took 0.4-1.1 s here, PGS's 200 sweeps 0.35 s (the README's Time limit).
//
// Rejected: a look at the clock at each of those calls. A tick is a comparison until the
// Deadline's stride (about a millisecond of calls at their mean cost) has passed.

#include <string>

#include "kit/run_limits.hpp"
#include "kit/solver.hpp"

namespace dart::simulation {
class World;
}

namespace pb::dart {

struct OutOfTime {};

class RunLimit {
 public:
  explicit RunLimit(const Settings& settings) : deadline_(settings) {}
  // One unit of work done; throws OutOfTime once the limit has passed or the sweep stops.
  void tick() {
    if (deadline_.tick()) throw OutOfTime{};
  }
  // Why the run stopped, for Result::message.
  std::string reason() const { return deadline_.reason(); }

 private:
  Deadline deadline_;
};

// World::step from t_k = k h under the run's limit: false where the limit passed before it or
// inside it (res then says time-limit at t_k; the world is not to be stepped again).
bool step_within(::dart::simulation::World& world, RunLimit& limit, long k, double h, Result& res);

}  // namespace pb::dart
