// What each compliant element restitutes, measured: README's table (reports/restitution.csv,
// written by scripts/main.sh; reports/make_report.py writes the table from it). Not a
// benchmark: one measurement per element and eps, printed as CSV on stdout.
//
// Every variant of the compliant solver is measured on a free impact through the solver itself
// (solvers/compliant/free_impact.hpp: CVODE at rtol 1e-12, nothing but the element acting).
// Hunt-Crossley's published closed forms of chi (Lankarani-Nikravesh, Flores), which are not
// variants, are measured on the scale-free integral of the same impact that calibrates chi
// (contact_law.hpp). Columns: element, rule (how its damping parameter is set), parameter
// (its name), eps, value (the parameter at eps), restitution, measured_by.

#include <cstdio>
#include <string>
#include <vector>

#include "cases/text.hpp"
#include "solvers/compliant/free_impact.hpp"
#include "kit/contact_elements/contact_law.hpp"

namespace {

using namespace pb::compliant;

constexpr const char* kSolver = "a free impact through the solver (CVODE at rtol 1e-12)";
constexpr const char* kIntegral = "the scale-free integral of the impact that calibrates chi (RK4)";

void row(const char* element, const char* rule, const char* parameter, double eps, double value, double e,
         const char* by) {
  std::printf("%s,%s,%s,%s,%s,%s,%s\n", element, rule, parameter, pb::format_number(eps).c_str(),
              pb::format_number(value).c_str(), pb::format_number(e).c_str(), by);
}

double measured(const char* variant, double eps) {
  const pb::Result r = free_impact(variant, eps);
  if (r.status != pb::Status::ok || r.isolated_impacts != 1) {
    std::fprintf(stderr, "poundbench_restitution: %s at eps %g: %s (%ld isolated impacts)\n", variant, eps,
                 r.message.c_str(), r.isolated_impacts);
    std::exit(1);
  }
  return r.restitution_low;
}

}  // namespace

int main() {
  std::printf("element,rule,parameter,eps,value,restitution,measured_by\n");
  for (double eps : {0.1, 0.3, 0.5, 0.6, 0.9}) {
    row("kelvin-voigt", "textbook zeta (exact for the unclamped element)", "zeta", eps, kelvin_voigt_zeta(eps),
        measured("kelvin-voigt", eps), kSolver);
    row("hunt-crossley", "chi calibrated", "chi", eps, hunt_crossley_chi(eps), measured("hunt-crossley", eps), kSolver);
    const double ln = lankarani_nikravesh_chi(eps), flores = flores_chi(eps);
    row("hunt-crossley", "Lankarani-Nikravesh chi = 3 (1 - eps^2) / 4", "chi", eps, ln, hunt_crossley_restitution(ln),
        kIntegral);
    row("hunt-crossley", "Flores chi = 8 (1 - eps) / (5 eps)", "chi", eps, flores, hunt_crossley_restitution(flores),
        kIntegral);
    row("jankowski", "zeta calibrated", "zeta", eps, jankowski_zeta(eps), measured("jankowski", eps), kSolver);
    row("jankowski-published", "his zeta = 9 sqrt(5) (1 - eps^2) / (2 eps (eps (9 pi - 16) + 16))", "zeta", eps,
        jankowski_published_zeta(eps), measured("jankowski-published", eps), kSolver);
  }
  row("hertz", "elastic (eps = 1 only)", "none", 1.0, 0.0, measured("hertz", 1.0), kSolver);
  return 0;
}
