#include "solvers/dart/variants.hpp"

namespace pb::dart {

namespace {

std::string_view lcp_name(Lcp lcp) {
  switch (lcp) {
    case Lcp::dantzig: return "dantzig";
    case Lcp::pgs: return "pgs";
    case Lcp::dantzig_then_pgs: return "dantzig, pgs on failure";
  }
  return "?";
}

}  // namespace

void add_config(NamedValues& out, const Config& config, const Settings& settings) {
  out.add("lcp", lcp_name(config.lcp));
  if (config.faithful) {
    if (config.lcp == Lcp::pgs) out.add("sweeps", kFaithfulPgsSweeps);
    out.add("contact", "gap constraint").add("restitution", "eps").add("springs", "explicit").add("units", "case");
  } else {
    // DART 6.12's compiled-in defaults (ContactConstraint.cpp), read in the normalised units.
    out.add("sweeps", 30).add("contact", "boxes via fcl").add("restitution", "eps per shape, product");
    out.add("bounce_threshold", 0.1).add("erp", 0.01).add("max_erv", 1e-3).add("cfm", 1e-5);
    out.add("friction", 1.0).add("springs", "joint (implicit)").add("units", "a_p = w_p = m0 = 1");
  }
  add_activation(out, "contacts", config.activation, settings);
}

std::vector<VariantInfo> variant_list() {
  return {
      {"dantzig-faithful",
       "a gap constraint per contact, Dantzig's LCP, restitution eps on every approach; explicit springs; contacts "
       "made before the gap closes (g + gamma h g' <= 0)"},
      {"pgs-faithful", "as dantzig-faithful, the LCP by projected Gauss-Seidel (" +
                           std::to_string(kFaithfulPgsSweeps) + " sweeps at most)"},
      {"default",
       "what a new user builds: boxes collided by FCL, restitution eps on each shape (their product acts), the "
       "joints' own springs and dampers, DART's defaults (no bounce below 0.1, push-out), Dantzig falling back to "
       "PGS; at a_p = w_p = 1"},
  };
}

}  // namespace pb::dart
