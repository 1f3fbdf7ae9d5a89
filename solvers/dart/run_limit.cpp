#include "solvers/dart/run_limit.hpp"

#include <dart/simulation/World.hpp>

namespace pb::dart {

bool step_within(::dart::simulation::World& world, RunLimit& limit, long k, double h, Result& res) {
  try {
    limit.tick();
    world.step();
    return true;
  } catch (const OutOfTime&) {
    res.status = Status::time_limit;
    res.message = limit.reason() + " at t = " + std::to_string(static_cast<double>(k) * h) + ", inside DART's step " +
                  std::to_string(k + 1);
    return false;
  }
}

}  // namespace pb::dart
