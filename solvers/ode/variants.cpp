#include "solvers/ode/variants.hpp"

#include <sstream>

namespace pb::ode {

void add_config(NamedValues& out, const Config& config, const Settings& settings) {
  out.add("stepper", config.stepper == Stepper::dantzig ? "dantzig" : "quickstep");
  if (config.stepper == Stepper::quickstep) out.add("iterations", config.iterations).add("sor", config.sor);
  out.add("erp", config.erp).add("cfm", config.cfm).add("bounce_vel", config.bounce_vel);
  out.add("surface_layer", config.surface_layer).add("max_vel", config.max_vel);
  add_activation(out, "contacts", config.activation, settings);
}

std::vector<VariantInfo> variant_list() {
  std::vector<VariantInfo> out;
  for (const Config& c : kVariants.configs) {
    std::ostringstream line;
    if (c.stepper == Stepper::dantzig)
      line << "dWorldStep (Dantzig's LCP)";
    else
      line << "dWorldQuickStep (" << c.iterations << " Gauss-Seidel sweeps, SOR " << c.sor << ")";
    line << "; ERP " << c.erp << ", CFM " << c.cfm << "; contacts "
         << (c.activation == Activation::predicted ? "made before the gap closes (g + gamma h g' <= 0)" : "made once the bodies overlap");
    out.push_back({c.name, line.str()});
  }
  return out;
}

}  // namespace pb::ode
