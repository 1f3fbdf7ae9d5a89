#pragma once
// The three ways this project runs DART: its constraint solver with a gap constraint of this
// project's own per contact (faithful: nothing but restitution shapes an impact, contacts by
// the rule every faithful time-stepper shares), by Dantzig's LCP or by projected
// Gauss-Seidel; and what a new DART user builds (default: boxes that FCL collides, the
// restitution on the shapes, each building's spring and damper on its own joint, DART's
// defaults, its Dantzig LCP falling back to PGS). Every value and the reason for it are in
// solvers/dart/README.md.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "kit/fixed_step.hpp"
#include "kit/named_values.hpp"
#include "kit/solver.hpp"
#include "kit/variant_table.hpp"

namespace pb::dart {

// The boxed LCP solver of DART's BoxedLcpConstraintSolver: Dantzig's pivoting (ODE's
// dSolveLCP, which DART carries), projected Gauss-Seidel, or Dantzig with PGS as the
// fallback where Dantzig fails (DART's default).
enum class Lcp { dantzig, pgs, dantzig_then_pgs };

struct Config {
  std::string_view name;
  // true: a GapConstraint per contact, explicit springs and dampers, the case's own units;
  // false: boxes via FCL, DART's ContactConstraint, joint springs and dampers, at the
  // suite's normalisation (a_p = w_p = m0 = 1).
  bool faithful = true;
  Lcp lcp = Lcp::dantzig;
  // When a contact takes part in a step (kit/fixed_step.hpp); the default variant's
  // contacts are FCL's, made at overlap.
  Activation activation = Activation::predicted;
};

inline constexpr VariantTable kVariants{
    std::array{
        Config{"dantzig-faithful", true, Lcp::dantzig, Activation::predicted},
        Config{"pgs-faithful", true, Lcp::pgs, Activation::predicted},
        Config{"default", false, Lcp::dantzig_then_pgs, Activation::overlap},
    },
    "dantzig-faithful"};

// PGS sweeps of pgs-faithful. Its sweeps are Gauss-Seidel without over-relaxation: a
// double contact of row3 contracts by 1 / ((1 + m0/m1)(1 + m0/m2)) per sweep, 0.83 with
// outer bodies ten times heavier than body 0, so 200 sweeps reach round-off there
// (0.83^200 ~ 1e-16); it stops earlier once a sweep changes nothing (tolerances 0).
inline constexpr int kFaithfulPgsSweeps = 200;

// Every setting of the configuration, for describe() after the variant and the step.
void add_config(NamedValues& out, const Config& config, const Settings& settings);

}  // namespace pb::dart
