#pragma once
// The four ways this project runs Simbody: its SemiExplicitEulerTimeStepper with rigid
// unilateral contacts (HardStopLower for the wall, PointPlaneFrictionlessContact between
// bodies) and Poisson's restitution, faithful (its PLUS or PGS impulse solver, constraint
// tolerance 1e-12, no position projection, contacts by the predicted rule every faithful
// time-stepper shares) or with the stepper's own settings (default); and compliant contact,
// HuntCrossleyForce elements integrated by Simbody's Runge-Kutta-Merson integrator. Every
// value and the reason for it are in solvers/simbody/README.md.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "kit/fixed_step.hpp"
#include "kit/named_values.hpp"
#include "solvers/simbody/model.hpp"
#include "kit/solver.hpp"
#include "kit/variant_table.hpp"

namespace pb::simbody {

struct Config {
  std::string_view name;
  Kind kind = Kind::faithful_plus;
  // When a unilateral contact takes part in a step (kit/fixed_step.hpp): faithful,
  // predicted; default, the stepper's own margin (g <= its constraint tolerance).
  Activation activation = Activation::predicted;
  bool time_stepper() const { return kind != Kind::hunt_crossley; }
};

inline constexpr VariantTable kVariants{
    std::array{
        Config{"plus-faithful", Kind::faithful_plus, Activation::predicted},
        Config{"pgs-faithful", Kind::faithful_pgs, Activation::predicted},
        Config{"default", Kind::stepper_default, Activation::overlap},
        Config{"hunt-crossley", Kind::hunt_crossley, Activation::overlap},
    },
    "plus-faithful"};

// The faithful variants' constraint tolerance, in the pulse's units (a_p / w_p^2, a_p / w_p):
// the stepper's impact capture speed is twice it, and a contact observes (takes no impact)
// when it approaches slower than a tenth of it, so impacts restitute eps down to 2e-12 a_p / w_p.
inline constexpr double kFaithfulConstraintTol = 1e-12;
// The default variant's: SemiExplicitEulerTimeStepper's own (its accuracy 1e-2 over 10).
inline constexpr double kStepperConstraintTol = 1e-3;

// hunt-crossley: the stiffness Pi term K when Settings::stiffness is 0 (the compliant
// solver's default); the integrator's accuracy when Settings::rtol is 0 (Pi1 within 3e-6 of
// its value at 1e-10 on the pair of the contract, at 0.8 of 1e-8's cost); and the speed at
// which its dissipation is calibrated to restitute eps, in a_p / w_p.
inline constexpr double kDefaultStiffness = 1e4;
inline constexpr double kDefaultAccuracy = 1e-6;
inline constexpr double kCalibrationSpeed = 1.0;
// Its report interval, h = T_min / N with this N: the history's and the monitor's rows. Pi1,
// the counts and the restitution of whole contacts are read at every internal step of the
// integrator (simbody_solver.cpp), which the reports do not limit.
inline constexpr int kHuntCrossleyReports = 64;

double stiffness(const Settings& settings);
double accuracy(const Settings& settings);

// Every setting of the configuration, for describe() after the variant (and the step).
void add_config(NamedValues& out, const Config& config, const Settings& settings);

}  // namespace pb::simbody
