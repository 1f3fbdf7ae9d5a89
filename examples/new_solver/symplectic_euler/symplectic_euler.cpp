#include "solvers/symplectic_euler/symplectic_euler.hpp"

#include <cmath>
#include <cstddef>

#include "kit/fixed_step.hpp"
#include "kit/named_values.hpp"

namespace pb::symplectic_euler {

namespace {

std::size_t ix(int i) { return static_cast<std::size_t>(i); }

int passes(const Settings& settings) { return static_cast<int>(own_value(settings, kOwnSettings, 0)); }

// One step from t_k: velocities from the springs, dampers and the ground load at t_k, then
// Newton's law on each contact predicted closed at mid-step (passes over the contacts in
// order: one is exact for an isolated impact, more approach a simultaneous one where contacts
// share a body), then positions from the new velocities.
class Engine final : public StepEngine {
 public:
  Engine(const System& sys, const Settings& set, double h)
      : StepEngine(sys), sys_(sys), h_(h), gamma_h_(set.gamma * h), passes_(passes(set)), before_(ix(sys.n_contacts())) {}

  StepOutcome step(long k, Result&) override {
    std::vector<double>& u = out_.u;
    std::vector<double>& v = out_.v;
    const double a_g = sys_.pulse.accel(static_cast<double>(k) * h_);
    for (int j = 0; j < sys_.n_contacts(); ++j) before_[ix(j)] = sys_.gap_rate(j, v.data());
    for (int i = 0; i < sys_.n_bodies(); ++i) {
      const Body& b = sys_.bodies[ix(i)];
      v[ix(i)] += h_ * (-(b.c * v[ix(i)] + b.k * u[ix(i)]) / b.m - a_g);
    }
    for (int j = 0; j < sys_.n_contacts(); ++j) {
      const bool closing = active(Activation::predicted, sys_.gap(j, u.data()), before_[ix(j)], gamma_h_);
      out_.entered[ix(j)] = closing && out_.force[ix(j)] == 0.0;
      out_.force[ix(j)] = 0.0;
    }
    for (int pass = 0; pass < passes_; ++pass)
      for (int j = 0; j < sys_.n_contacts(); ++j) {
        const double rate = sys_.gap_rate(j, v.data());
        if (!active(Activation::predicted, sys_.gap(j, u.data()), before_[ix(j)], gamma_h_) || rate >= 0.0) continue;
        // The impulse per unit time that makes the gap rate -eps times its rate before the step.
        const double target = before_[ix(j)] < 0.0 ? -sys_.eps * before_[ix(j)] : 0.0;
        if (rate >= target) continue;
        const int l = sys_.left(j), r = sys_.right(j);
        const double inv_m = 1.0 / sys_.bodies[ix(r)].m + (l == kWall ? 0.0 : 1.0 / sys_.bodies[ix(l)].m);
        const double impulse = (target - rate) / inv_m;
        v[ix(r)] += impulse / sys_.bodies[ix(r)].m;
        if (l != kWall) v[ix(l)] -= impulse / sys_.bodies[ix(l)].m;
        out_.force[ix(j)] += impulse / h_;
      }
    for (int i = 0; i < sys_.n_bodies(); ++i) u[ix(i)] += h_ * v[ix(i)];
    return StepOutcome::taken;
  }

 private:
  const System& sys_;
  double h_, gamma_h_;
  int passes_;
  std::vector<double> before_;  // each contact's gap rate at t_k
};

}  // namespace

Result solve(const System& system, const Settings& settings) {
  if (std::string bad = check(settings); !bad.empty()) return failed(bad);  // solve() may be called unchecked
  if (system.yields()) return yielding_refused("this example integrates linear springs only");
  StepPlan plan;
  if (Result r = plan_steps(system, settings, kDefaultSteps, kDefaultStepCap, plan); r.status != Status::ok) return r;
  Engine engine(system, settings, plan.h);
  return run_steps(system, settings, plan, engine);
}

std::string describe(const Settings& settings) {
  NamedValues out;
  add_step(out, settings, kDefaultSteps);
  add_activation(out, "contacts", Activation::predicted, settings);
  out.add("passes", passes(settings));
  return out.json();
}

std::string check(const Settings& settings) {
  if (!settings.variant.empty() && settings.variant != "predicted")
    return "variant: unknown '" + settings.variant + "' (known: predicted)";
  if (std::string bad = check_step(settings, kDefaultSteps); !bad.empty()) return bad;
  const double k = own_value(settings, kOwnSettings, 0);
  if (!(k >= 1.0 && k <= 100.0 && k == std::floor(k))) return "passes: must be a whole number from 1 to 100";
  return check_activation(Activation::predicted, settings);
}

std::vector<VariantInfo> variant_list() {
  return {{"predicted", "symplectic Euler, Newton impacts on contacts predicted closed at mid-step"}};
}

}  // namespace pb::symplectic_euler
