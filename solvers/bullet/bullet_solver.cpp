#include "solvers/bullet/bullet_solver.hpp"

#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <optional>

#include "solvers/bullet/engine.hpp"
#include "kit/fixed_step.hpp"
#include "kit/variant_table.hpp"

namespace pb::bullet {

namespace {

// Bullet behind the shared step loop (kit/fixed_step.hpp).
class Stepper : public StepEngine {
 public:
  Stepper(const System& sys, const Config& config, double h, double gamma)
      : StepEngine(sys), sys_(sys), h_(h), world_(sys, config, h, gamma, out_.u, out_.v) {}

  StepOutcome step(long k, Result&) override {
    world_.step(static_cast<double>(k) * h_);
    for (int i = 0; i < sys_.n_bodies(); ++i) {
      out_.u[ix(i)] = world_.u(i);
      out_.v[ix(i)] = world_.v(i);
    }
    for (int j = 0; j < sys_.n_contacts(); ++j) {
      out_.force[ix(j)] = world_.impulse(j) / h_;
      out_.entered[ix(j)] = world_.added(j) ? 1 : 0;  // a new manifold point
    }
    return StepOutcome::taken;
  }

  void finish(Result& res) override {
    world_.finish_springs(res);
    if (const int fb = world_.fallbacks(); fb > 0) {
      if (!res.message.empty()) res.message += "; ";
      res.message +=
          "the MLCP solver failed in " + std::to_string(fb) + " steps (Bullet fell back to sequential impulse)";
    }
  }

 private:
  const System& sys_;
  double h_;
  World world_;
};

Result run(const System& sys, const Settings& set, const Config& config) {
  StepPlan plan;
  if (Result r = plan_steps(sys, set, kDefaultSteps, kDefaultStepCap, plan); r.status != Status::ok) return r;
  Stepper engine(sys, config, plan.h, set.gamma);
  return run_steps(sys, set, plan, engine);
}

}  // namespace

Result solve_with(const System& system, const Settings& settings, const Config& config) {
  try {
    return run(system, settings, config);
  } catch (const std::exception& e) {
    return failed(e.what());
  }
}

Result solve(const System& system, const Settings& settings) {
  const std::optional<Config> config = kVariants.find(settings.variant);
  if (!config) return failed("unknown variant '" + settings.variant + "'");
  return solve_with(system, settings, *config);
}

std::string describe(const Settings& settings) {
  return describe_variant(kVariants, settings, kDefaultSteps);
}

std::string check(const Settings& settings) {
  return check_variant("bullet", kVariants, settings, kDefaultSteps);
}

}  // namespace pb::bullet
