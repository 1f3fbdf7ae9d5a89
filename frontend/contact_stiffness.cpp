#include "frontend/contact_stiffness.hpp"

#include <cmath>
#include <string>

#include "frontend/errors.hpp"
#include "cases/physical.hpp"

namespace pb::app {

void apply_k_contact(const Case& c, std::string_view solver, Settings& settings, double k, bool stiffness_given) {
  if (stiffness_given) throw BadInput("--k-contact: not with --stiffness (give the stiffness one way)");
  if (!physical(c))
    throw BadInput("--k-contact: needs a case in physical units (--t0, --gap, ...): its unit of mass is m0's");
  if (!(std::isfinite(k) && k > 0.0)) throw BadInput("--k-contact: must be finite and > 0");
  settings.stiffness = stiffness_pi_term(c, k, hertz_contact(solver, settings));
}

}  // namespace pb::app
