#include "solvers/bullet/variants.hpp"

#include <array>
#include <sstream>

#include "solvers/bullet/engine.hpp"

namespace pb::bullet {

namespace {

constexpr std::array kVariants = {
    Config{"si-faithful", Engine::si, true},
    Config{"si-default", Engine::si, false},
    Config{"mlcp-dantzig-faithful", Engine::mlcp_dantzig, true},
    Config{"mlcp-dantzig-default", Engine::mlcp_dantzig, false},
    Config{"mlcp-lemke-faithful", Engine::mlcp_lemke, true},
    Config{"mlcp-lemke-default", Engine::mlcp_lemke, false},
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
  if (name.empty()) name = kDefaultVariant;
  for (const Config& c : kVariants)
    if (c.name == name) return c;
  return std::nullopt;
}

std::string variant_names() {
  std::string out;
  for (const Config& c : kVariants) {
    if (!out.empty()) out += ", ";
    out += c.name;
  }
  return out;
}

std::string describe(const Config& config, std::string_view step) {
  // The step does not change any of these settings; 1 stands for it.
  const btContactSolverInfo info = solver_info(config, 1.0);
  std::ostringstream out;
  out << "variant=" << config.name << ";" << step << ";solver=" << solver_name(config.engine)
      << ";iterations=" << info.m_numIterations << ";erp2=" << info.m_erp2
      << ";split_impulse=" << info.m_splitImpulse;
  if (info.m_splitImpulse) out << ";split_threshold=" << info.m_splitImpulsePenetrationThreshold;
  out << ";restitution_threshold=" << info.m_restitutionVelocityThreshold
      << ";warmstart=" << ((info.m_solverMode & SOLVER_USE_WARMSTARTING) ? info.m_warmstartingFactor : 0.0f)
      << ";restitution=" << (config.faithful ? "eps" : "product") << ";contact=overlap;precision=single";
  return out.str();
}

}  // namespace pb::bullet
