#include "solvers/bullet/variants.hpp"

#include "solvers/bullet/engine.hpp"

namespace pb::bullet {

namespace {

// A constraint solver's name in describe() and the Bullet classes that make it.
struct EngineWords {
  std::string_view name, classes;
};
EngineWords words(Engine e) {
  switch (e) {
    case Engine::si: return {"si", "btSequentialImpulseConstraintSolver"};
    case Engine::mlcp_dantzig: return {"mlcp-dantzig", "btMLCPSolver with btDantzigSolver"};
    case Engine::mlcp_lemke: return {"mlcp-lemke", "btMLCPSolver with btLemkeSolver"};
  }
  return {"?", "?"};
}

}  // namespace

void add_config(NamedValues& out, const Config& config, const Settings& settings) {
  // The step does not change any of these settings; 1 stands for it.
  const btContactSolverInfo info = solver_info(config, 1.0);
  out.add("solver", words(config.engine).name).add("iterations", info.m_numIterations);
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
    std::string line(words(c.engine).classes);
    if (c.engine == Engine::si) line += ", " + std::to_string(solver_info(c, 1.0).m_numIterations) + " sweeps";
    line += c.faithful ? "; restitution eps alone (no push-out, threshold or warm start)"
                       : "; Bullet's btContactSolverInfo defaults, restitution the bodies' product";
    line += c.activation == Activation::predicted ? "; contacts made before the gap closes (g + gamma h g' <= 0)"
                                                  : "; contacts made once the bodies overlap";
    out.push_back({c.name, line});
  }
  return out;
}

}  // namespace pb::bullet
