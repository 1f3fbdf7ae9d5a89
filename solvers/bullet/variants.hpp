#pragma once
// The seven ways this project runs Bullet: a constraint solver (sequential impulse, or the
// MLCP solver with Dantzig's or Lemke's algorithm) times a configuration (faithful:
// nothing but restitution shapes an impact, contacts by the Moreau-Jean rule every faithful
// time-stepper shares; default: Bullet's own btContactSolverInfo with only the restitution
// set, contacts at overlap, as a new user gets), and si-overlap: sequential impulse,
// faithful but for its contacts, made at overlap as Bullet's collision detection makes
// them. Every value and the reason for it are in solvers/bullet/README.md; the solver
// settings are set in one place, solver_info() in engine.cpp, and describe() prints what
// that function returns.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "kit/fixed_step.hpp"
#include "kit/named_values.hpp"
#include "kit/solver.hpp"
#include "kit/variant_table.hpp"

namespace pb::bullet {

// Which btConstraintSolver gets the contacts of a step.
//   si:           btSequentialImpulseConstraintSolver (projected Gauss-Seidel on impulses)
//   mlcp_dantzig: btMLCPSolver with btDantzigSolver (direct, ODE's dLCP)
//   mlcp_lemke:   btMLCPSolver with btLemkeSolver (pivoting, box bounds by doubling)
enum class Engine { si, mlcp_dantzig, mlcp_lemke };

struct Config {
  std::string_view name;
  Engine engine = Engine::si;
  bool faithful = true;  // false: Bullet's btContactSolverInfo defaults, restitution per body
  // When contact j has a manifold point in a step (kit/fixed_step.hpp).
  Activation activation = Activation::predicted;
};

// Sequential-impulse sweeps per step in the faithful configuration. A double contact of
// row3 contracts by 1 / ((1 + m0/m1)(1 + m0/m2)) per sweep, 0.83 for outer bodies ten
// times heavier than body 0 (Pi6 = Pi8 = 0.1): 100 sweeps reach single precision there
// (0.83^100 ~ 1e-8); Bullet's default 10 leave 15% of the impulse unsolved (README).
inline constexpr int kFaithfulIterations = 100;

// si-overlap keeps what Bullet's own contact generation gives a user (a point once the
// shapes touch) with the faithful solver settings: the one difference from si-faithful is
// when a contact starts. Only for si: the three faithful solvers agree to the bit on single
// contacts, so MLCP twins would show the same difference again.
inline constexpr VariantTable kVariants{
    std::array{
        Config{"si-faithful", Engine::si, true, Activation::predicted},
        Config{"si-overlap", Engine::si, true, Activation::overlap},
        Config{"si-default", Engine::si, false, Activation::overlap},
        Config{"mlcp-dantzig-faithful", Engine::mlcp_dantzig, true, Activation::predicted},
        Config{"mlcp-dantzig-default", Engine::mlcp_dantzig, false, Activation::overlap},
        Config{"mlcp-lemke-faithful", Engine::mlcp_lemke, true, Activation::predicted},
        Config{"mlcp-lemke-default", Engine::mlcp_lemke, false, Activation::overlap},
    },
    "si-faithful"};

// Every setting that shapes an impact (solver, iterations, ..., the activation rule and the
// gamma of settings where it uses one), read back from the solver info a run uses, for
// describe() after the variant and the step.
void add_config(NamedValues& out, const Config& config, const Settings& settings);

// The named variants with one line each, made from their settings (`poundbench solvers`).
std::vector<VariantInfo> variant_list();

}  // namespace pb::bullet
