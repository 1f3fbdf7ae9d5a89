#pragma once
// The four ways this project runs the Open Dynamics Engine: a stepper (ODE's Dantzig LCP
// in dWorldStep, or its projected Gauss-Seidel in dWorldQuickStep) times a configuration
// (faithful: nothing but restitution shapes an impact; default: what a new ODE user gets).
// Every value and the reason for it are in solvers/ode/README.md.

#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "kit/fixed_step.hpp"
#include "kit/named_values.hpp"
#include "kit/solver.hpp"
#include "kit/variant_table.hpp"

namespace pb::ode {

enum class Stepper { dantzig, quickstep };

struct Config {
  std::string_view name;
  Stepper stepper = Stepper::dantzig;
  int iterations = 20;   // quickstep: PGS sweeps per step (dWorldSetQuickStepNumIterations)
  double sor = 1.3;      // quickstep: over-relaxation (dWorldSetQuickStepW)
  double erp = 0.0;      // dWorldSetERP: fraction of the depth pushed out per step
  double cfm = 0.0;      // dWorldSetCFM: constraint softness, velocity per unit force
  double bounce_vel = 0.0;     // dSurfaceParameters::bounce_vel: no bounce at or below it
  double surface_layer = 0.0;  // dWorldSetContactSurfaceLayer: depth left uncorrected
  double max_vel = 0.0;        // dWorldSetContactMaxCorrectingVel: cap of the push-out
  // When a contact joint is made for a step (kit/fixed_step.hpp): faithful, the
  // Moreau-Jean rule g + gamma h g' <= 0; default, at overlap, as collision detection would.
  Activation activation = Activation::predicted;
};

// faithful: no push-out (ERP 0, and a zero cap on what push-out there could be), rigid
// rows (CFM 0), bounce at every approach speed, contacts made by the Moreau-Jean rule
// (g + gamma h g' <= 0, the one every faithful time-stepper shares).
// quickstep-faithful keeps ODE's SOR 1.3 and takes 50 sweeps: enough to converge the
// two coupled contacts of row3 to round-off (see README).
// default: ODE 0.16's world defaults in double precision (ERP 0.2, CFM 1e-10, no surface
// layer, no cap; quickstep 20 sweeps at SOR 1.3), bounce_vel 0 (the field has no default;
// zero-initialised), and contacts only where the bodies overlap, as collision detection
// would report them.
inline constexpr double kNoCap = std::numeric_limits<double>::infinity();
inline constexpr VariantTable kVariants{
    std::array{
        Config{"dantzig-faithful", Stepper::dantzig, 20, 1.3, 0.0, 0.0, 0.0, 0.0, 0.0, Activation::predicted},
        Config{"dantzig-default", Stepper::dantzig, 20, 1.3, 0.2, 1e-10, 0.0, 0.0, kNoCap, Activation::overlap},
        Config{"quickstep-faithful", Stepper::quickstep, 50, 1.3, 0.0, 0.0, 0.0, 0.0, 0.0, Activation::predicted},
        Config{"quickstep-default", Stepper::quickstep, 20, 1.3, 0.2, 1e-10, 0.0, 0.0, kNoCap, Activation::overlap},
    },
    "dantzig-faithful"};

// Every setting of the configuration (stepper, ..., the activation rule and the gamma of
// settings where it uses one), for describe() after the variant and the step.
void add_config(NamedValues& out, const Config& config, const Settings& settings);

// The named variants with one line each, made from their settings (`poundbench solvers`).
std::vector<VariantInfo> variant_list();

}  // namespace pb::ode
