#pragma once
// The four ways this project runs the Open Dynamics Engine: a stepper (ODE's Dantzig LCP
// in dWorldStep, or its projected Gauss-Seidel in dWorldQuickStep) times a configuration
// (faithful: nothing but restitution shapes an impact; default: what a new ODE user gets).
// Every value and the reason for it are in solvers/ode/README.md.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "solvers/fixed_step.hpp"
#include "solvers/named_values.hpp"
#include "solvers/solver.hpp"

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
  // When a contact joint is made for a step (solvers/fixed_step.hpp): faithful, the
  // Moreau-Jean rule g + gamma h g' <= 0; default, at overlap, as collision detection would.
  Activation activation = Activation::predicted;
};

inline constexpr std::string_view kDefaultVariant = "dantzig-faithful";

// The named variants: dantzig-faithful, dantzig-default, quickstep-faithful, quickstep-default.
std::span<const Config> variants();
// The variant of that name; the empty name is kDefaultVariant.
std::optional<Config> find_variant(std::string_view name);

// Every setting of the configuration (stepper, ..., the activation rule and the gamma of
// settings where it uses one), for describe() after the variant and the step.
void add_config(NamedValues& out, const Config& config, const Settings& settings);

// The named variants with one line each, made from their settings (`poundbench solvers`).
std::vector<VariantInfo> variant_list();

}  // namespace pb::ode
