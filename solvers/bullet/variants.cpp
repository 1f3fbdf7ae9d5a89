#include "solvers/bullet/variants.hpp"

#include <array>

#include "solvers/bullet/engine.hpp"
#include "solvers/variant_table.hpp"

namespace pb::bullet {

namespace {

constexpr Activation kPredicted = Activation::predicted, kOverlap = Activation::overlap;

// si-overlap keeps what Bullet's own contact generation gives a user (a point once the
// shapes touch) with the faithful solver settings: the one difference from si-faithful is
// when a contact starts. Only for si: the three faithful solvers agree to the bit on single
// contacts, so MLCP twins would show the same difference again.
constexpr std::array kVariants = {
    Config{"si-faithful", Engine::si, true, kPredicted},
    Config{"si-overlap", Engine::si, true, kOverlap},
    Config{"si-default", Engine::si, false, kOverlap},
    Config{"mlcp-dantzig-faithful", Engine::mlcp_dantzig, true, kPredicted},
    Config{"mlcp-dantzig-default", Engine::mlcp_dantzig, false, kOverlap},
    Config{"mlcp-lemke-faithful", Engine::mlcp_lemke, true, kPredicted},
    Config{"mlcp-lemke-default", Engine::mlcp_lemke, false, kOverlap},
};

std::string_view solver_name(Engine e) {
  switch (e) {
    case Engine::si: return "si";
    case Engine::mlcp_dantzig: return "mlcp-dantzig";
    case Engine::mlcp_lemke: return "mlcp-lemke";
  }
  return "?";
}

}  // namespace

std::span<const Config> variants() { return kVariants; }

std::optional<Config> find_variant(std::string_view name) {
  return find_named(std::span<const Config>(kVariants), name, kDefaultVariant);
}

void add_config(NamedValues& out, const Config& config, const Settings& settings) {
  // The step does not change any of these settings; 1 stands for it.
  const btContactSolverInfo info = solver_info(config, 1.0);
  out.add("solver", solver_name(config.engine)).add("iterations", info.m_numIterations);
  out.add("erp2", info.m_erp2).add("split_impulse", info.m_splitImpulse);
  if (info.m_splitImpulse) out.add("split_threshold", info.m_splitImpulsePenetrationThreshold);
  out.add("restitution_threshold", info.m_restitutionVelocityThreshold);
  out.add("warmstart", (info.m_solverMode & SOLVER_USE_WARMSTARTING) ? info.m_warmstartingFactor : 0.0f);
  out.add("restitution", config.faithful ? "eps" : "product");
  add_activation(out, "contact", config.activation, settings);
  out.add("precision", "single");
}

std::vector<VariantInfo> variant_list() {
  std::vector<VariantInfo> out;
  for (const Config& c : kVariants) {
    std::string line;
    switch (c.engine) {
      case Engine::si:
        line = "btSequentialImpulseConstraintSolver, " + std::to_string(solver_info(c, 1.0).m_numIterations) + " sweeps";
        break;
      case Engine::mlcp_dantzig: line = "btMLCPSolver with btDantzigSolver"; break;
      case Engine::mlcp_lemke: line = "btMLCPSolver with btLemkeSolver"; break;
    }
    line += c.faithful ? "; restitution eps alone (no push-out, threshold or warm start)"
                       : "; Bullet's btContactSolverInfo defaults, restitution the bodies' product";
    line += c.activation == Activation::predicted ? "; contacts made before the gap closes (g + gamma h g' <= 0)"
                                                  : "; contacts made once the bodies overlap";
    out.push_back({c.name, line});
  }
  return out;
}

}  // namespace pb::bullet
