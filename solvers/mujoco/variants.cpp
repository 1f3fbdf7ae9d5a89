#include "solvers/mujoco/variants.hpp"

#include "solvers/mujoco/contact.hpp"

namespace pb::mujoco {

double contact_steps(const Settings& settings) {
  return settings.contact_steps > 0.0 ? settings.contact_steps : kDefaultContactSteps;
}

IntegratorWords words(Integrator i) {
  switch (i) {
    case Integrator::euler: return {"euler", "semi-implicit Euler (damping implicit)"};
    case Integrator::implicit: return {"implicit", "Euler implicit in velocity"};
    case Integrator::rk4: return {"rk4", "4th-order Runge-Kutta"};
  }
  return {"?", "?"};
}

void add_config(NamedValues& out, const Config& config, const Settings& settings) {
  out.add("integrator", words(config.integrator).name);
  if (config.calibrated) {
    out.add("contact_steps", contact_steps(settings));
    out.add("solref", "direct, calibrated to eps").add("solimp", kImpedance);
    out.add("units", "pulse").add("tolerance", 1e-12);
  } else {
    const ContactParameters p = default_contact();
    out.add("solref", "0.02 1").add("solimp", "0.9 0.95 0.001 0.5 2").add("margin", p.margin);
    out.add("units", "case").add("tolerance", 1e-8);
  }
  out.add("contacts", "overlap");
}

std::vector<VariantInfo> variant_list() {
  std::vector<VariantInfo> out;
  for (const Config& c : kVariants.configs) {
    std::string line(words(c.integrator).summary);
    line += c.calibrated ? "; contacts spring-dampers calibrated to eps, time constant --contact-steps steps"
                         : "; MuJoCo's default contacts (solref 0.02 1, solimp 0.9 0.95), eps not used";
    out.push_back({c.name, line});
  }
  return out;
}

}  // namespace pb::mujoco
