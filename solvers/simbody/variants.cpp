#include "solvers/simbody/variants.hpp"

#include <cmath>

#include "solvers/simbody/simbody_solver.hpp"

namespace pb::simbody {

double stiffness(const Settings& settings) { return settings.stiffness > 0.0 ? settings.stiffness : kDefaultStiffness; }

double accuracy(const Settings& settings) { return settings.rtol > 0.0 ? settings.rtol : kDefaultAccuracy; }

void add_config(NamedValues& out, const Config& config, const Settings& settings) {
  switch (config.kind) {
    case Kind::faithful_plus:
    case Kind::faithful_pgs:
      out.add("stepper", "semi-explicit euler").add("impulse_solver", config.kind == Kind::faithful_pgs ? "pgs" : "plus");
      out.add("restitution", "poisson").add("constraint_tol", kFaithfulConstraintTol).add("projection", "none");
      add_activation(out, "contacts", config.activation, settings);
      break;
    case Kind::stepper_default:
      out.add("stepper", "semi-explicit euler").add("impulse_solver", "plus").add("restitution", "poisson");
      out.add("constraint_tol", kStepperConstraintTol).add("projection", "bilateral").add("contacts", "margin");
      break;
    case Kind::hunt_crossley:
      add_stiffness(out, settings, stiffness(settings));
      out.add("rtol", accuracy(settings));
      out.add("integrator", "runge-kutta-merson").add("calibration_speed", kCalibrationSpeed);
      out.add("reports", kHuntCrossleyReports);
      break;
  }
  out.add("units", "a_p = w_p = m0 = 1");
}

std::vector<VariantInfo> variant_list() {
  return {
      {"plus-faithful",
       "SemiExplicitEulerTimeStepper, PLUS impulse solver, Poisson restitution eps, constraint tolerance 1e-12, no "
       "position projection; contacts made before the gap closes (g + gamma h g' <= 0)"},
      {"pgs-faithful", "as plus-faithful, with the stepper's PGS impulse solver"},
      {"default",
       "SemiExplicitEulerTimeStepper with its own settings (constraint tolerance 1e-3: contacts within 1e-3 of "
       "closing, no bounce below 2e-3, bilateral position projection); at a_p = w_p = 1"},
      {"hunt-crossley",
       "compliant: HuntCrossleyForce (Hertz, dissipation calibrated to eps at impact speed a_p/w_p), --stiffness K; "
       "Runge-Kutta-Merson at --rtol"},
  };
}

}  // namespace pb::simbody
