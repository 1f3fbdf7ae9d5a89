#include "solvers/dart/dart_solver.hpp"

#include <memory>

#include "solvers/dart/engines.hpp"
#include "solvers/dart/variants.hpp"
#include "kit/fixed_step.hpp"
#include "kit/variant_table.hpp"

namespace pb::dart {

namespace {

Result run(const System& sys, const Settings& set, const Config& config) {
  for (const Body& b : sys.bodies)
    if (!(b.m > 0.0 && std::isfinite(b.m)) || !std::isfinite(b.k) || !std::isfinite(b.c))
      return failed("every body needs a finite positive mass and a finite stiffness and damping");
  // Debian's DART asserts (and so aborts the process) on a joint spring or damper below zero.
  if (!config.faithful)
    for (const Body& b : sys.bodies)
      if (b.k < 0.0 || b.c < 0.0)
        return failed("the default variant's joint springs and dampers must be >= 0: DART's joints take no unstable spring");
  StepPlan plan;
  if (Result r = plan_steps(sys, set, kDefaultSteps, kDefaultStepCap, plan); r.status != Status::ok) return r;
  // The limit holds from here, through the model's set-up (run_limit.hpp).
  RunLimit limit(set);
  std::unique_ptr<StepEngine> engine;
  try {
    engine = config.faithful ? make_faithful(sys, config, set, plan.h, limit) : make_default(sys, config, plan.h, limit);
  } catch (const OutOfTime&) {
    Result r;
    r.status = Status::time_limit;
    r.message = limit.reason() + " in DART's set-up of " + std::to_string(sys.n_bodies()) + " bodies";
    r.step = plan.h;
    return r;
  }
  return run_steps(sys, set, plan, *engine);
}

}  // namespace

Result solve(const System& system, const Settings& settings) {
  return solve_linear_variant(kVariants, system, settings,
                              "dart's bodies have linear springs (explicit, or the joints' own in its default); the "
                              "bilinear law is not applied (moreau-jean, ode and bullet apply it)",
                              &run, "DART: ");
}

std::string describe(const Settings& settings) {
  return describe_variant(kVariants, settings, kDefaultSteps);
}

std::string check(const Settings& settings) {
  return check_variant("dart", kVariants, settings, kDefaultSteps);
}

}  // namespace pb::dart
