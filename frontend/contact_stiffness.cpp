#include "frontend/contact_stiffness.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "frontend/errors.hpp"
#include "cases/physical.hpp"
#include "solvers/registry.hpp"

namespace pb::app {

void apply_k_contact(const Case& c, std::string_view solver, Settings& settings, double k, bool stiffness_given) {
  if (stiffness_given) throw BadInput("--k-contact: not with --stiffness (give the stiffness one way)");
  if (!physical(c))
    throw BadInput("--k-contact: needs a case in physical units (--t0, --gap, ...): its unit of mass is m0's");
  if (!(std::isfinite(k) && k > 0.0)) throw BadInput("--k-contact: must be finite and > 0");
  const SolverInfo* info = find_solver(solver);  // an unknown one is refused by its check, after
  settings.stiffness = stiffness_pi_term(c, k, info && hertz_contact(*info, settings));
  settings.k_contact = k;
}

const SolverInfo& checked_solver_k_contact(const SolverFlags& flags, const GivenSolverFlag& given, bool k_contact) {
  if (!k_contact) return checked_solver(flags, given);
  try {
    return checked_solver(flags, [&](std::string_view flag) { return flag == "--stiffness" || (given && given(flag)); });
  } catch (const BadInput& e) {
    constexpr std::string_view kStiffness = "--stiffness:";
    const std::string what = e.what();
    if (!what.starts_with(kStiffness)) throw;
    const std::string reason = what.substr(kStiffness.size());
    if (reason.starts_with(" not used by")) throw BadInput("--k-contact:" + reason);
    char K[32];
    std::snprintf(K, sizeof K, "%.6g", flags.settings.stiffness);
    throw BadInput("--k-contact: gives --stiffness K = " + std::string(K) + ":" + reason);
  }
}

}  // namespace pb::app
