#include "solvers/bullet/variants.hpp"

#include "solvers/bullet/engine.hpp"

namespace pb::bullet {

namespace {

std::string_view solver_name(Engine e) {
  switch (e) {
    case Engine::si: return "si";
    case Engine::mlcp_dantzig: return "mlcp-dantzig";
    case Engine::mlcp_lemke: return "mlcp-lemke";
  }
  return "?";
}

}  // namespace

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
  for (const Config& c : kVariants.configs) {
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
