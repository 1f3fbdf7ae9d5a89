#include "studies/physical_settings.hpp"

#include <cmath>
#include <string>

#include "cases/physical.hpp"
#include "cases/system.hpp"
#include "cases/text.hpp"
#include "studies/settings_list.hpp"

namespace pb {

namespace {

// Cases of one set of buildings map a value to the same Pi form up to the round-off of
// their own Pi terms (a record's w_p and a_p as read, ~1e-16 each); 1e-12 leaves room for
// that and refuses any real difference in T_min or m0 w0^2.
constexpr double kSameMapping = 1e-12;

}  // namespace

void resolve_physical_settings(SettingsList& list, std::span<const Case> cases, std::string_view source) {
  for (std::size_t k = 0; k < list.runs.size() && k < list.physical.size(); ++k) {
    const PhysicalSetting& given = list.physical[k];
    if (!given.given()) continue;
    SweepRun& run = list.runs[k];
    const std::string where = std::string(source) + ": run " + std::to_string(k) + " (" +
                              std::string(run.solver->name) + (run.settings.variant.empty() ? "" : " " + run.settings.variant) + ")";
    const auto fail = [&](std::string_view field, const std::string& why) {
      throw SettingsListError(where + ": " + std::string(field) + ": " + why);
    };
    double wh = 0, stiffness = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const Case& c = cases[i];
      const System system = make_system(c);
      const auto agree = [&](std::string_view field, double& first, double x) {
        if (i == 0) first = x;
        else if (!(std::abs(x - first) <= kSameMapping * std::abs(first)))
          fail(field, "maps to " + format_number(first) + " at point 0 and " + format_number(x) + " at point " +
                          std::to_string(i) + " (a study runs one setting over its cases: give one case, or steps/" +
                          "stiffness in Pi terms)");
      };
      if (given.h_s > 0.0) agree("h_s", wh, step_pi_term(system, given.h_s));
      if (given.k_contact > 0.0) {
        if (!physical(c))
          fail("k_contact", "point " + std::to_string(i) + " is in Pi terms; a stiffness in N/m needs a case in "
                            "physical units (its unit of mass is m0's)");
        agree("k_contact", stiffness, stiffness_pi_term(c, given.k_contact, hertz_contact(*run.solver, run.settings)));
      }
    }
    if (given.h_s > 0.0) run.settings.wh = wh;
    if (given.k_contact > 0.0) run.settings.stiffness = stiffness;
    if (const std::string bad = run.solver->check(run.settings); !bad.empty())
      fail(given.h_s > 0.0 && bad.rfind("wh", 0) == 0 ? "h_s" : given.k_contact > 0.0 && bad.rfind("stiffness", 0) == 0 ? "k_contact" : "settings",
           clip(bad, kMaxEchoedReason));
  }
}

}  // namespace pb
