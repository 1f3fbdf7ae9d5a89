#include "solvers/ode/variants.hpp"

#include <array>
#include <limits>
#include <sstream>

#include "solvers/variant_table.hpp"

namespace pb::ode {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// faithful: no push-out (ERP 0, and a zero cap on what push-out there could be), rigid
// rows (CFM 0), bounce at every approach speed, contacts made by the Moreau-Jean rule
// (g + gamma h g' <= 0, the one every faithful time-stepper shares).
// quickstep-faithful keeps ODE's SOR 1.3 and takes 50 sweeps: enough to converge the
// two coupled contacts of row3 to round-off (see README).
// default: ODE 0.16's world defaults in double precision (ERP 0.2, CFM 1e-10, no surface
// layer, no cap; quickstep 20 sweeps at SOR 1.3), bounce_vel 0 (the field has no default;
// zero-initialised), and contacts only where the bodies overlap, as collision detection
// would report them.
constexpr std::array kVariants = {
    Config{"dantzig-faithful", Stepper::dantzig, 20, 1.3, 0.0, 0.0, 0.0, 0.0, 0.0, Activation::predicted},
    Config{"dantzig-default", Stepper::dantzig, 20, 1.3, 0.2, 1e-10, 0.0, 0.0, kInf, Activation::overlap},
    Config{"quickstep-faithful", Stepper::quickstep, 50, 1.3, 0.0, 0.0, 0.0, 0.0, 0.0, Activation::predicted},
    Config{"quickstep-default", Stepper::quickstep, 20, 1.3, 0.2, 1e-10, 0.0, 0.0, kInf, Activation::overlap},
};

}  // namespace

std::span<const Config> variants() { return kVariants; }

std::optional<Config> find_variant(std::string_view name) {
  return find_named(std::span<const Config>(kVariants), name, kDefaultVariant);
}

void add_config(NamedValues& out, const Config& config, const Settings& settings) {
  out.add("stepper", config.stepper == Stepper::dantzig ? "dantzig" : "quickstep");
  if (config.stepper == Stepper::quickstep) out.add("iterations", config.iterations).add("sor", config.sor);
  out.add("erp", config.erp).add("cfm", config.cfm).add("bounce_vel", config.bounce_vel);
  out.add("surface_layer", config.surface_layer).add("max_vel", config.max_vel);
  add_activation(out, "contacts", config.activation, settings);
}

std::vector<VariantInfo> variant_list() {
  std::vector<VariantInfo> out;
  for (const Config& c : kVariants) {
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
