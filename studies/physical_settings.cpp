#include "studies/physical_settings.hpp"

#include <string>

#include "cases/physical.hpp"
#include "cases/text.hpp"
#include "studies/settings_list.hpp"

namespace pb {

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
    // A stiffness in N/m: each case takes its own Pi term from it (sweep/sweep.hpp, run_point),
    // so each case must be in physical units (its unit of mass is m0's).
    for (std::size_t i = 0; i < cases.size() && given.k_contact > 0.0; ++i)
      if (!physical(cases[i]))
        fail("k_contact", "point " + std::to_string(i) + " is in Pi terms; a stiffness in N/m needs a case in "
                          "physical units (its unit of mass is m0's)");
    if (given.k_contact > 0.0) run.settings.k_contact = given.k_contact;
    // A step in seconds is the same step on every case (each case's N follows from it): the
    // solvers take it as it is (Settings::h_s, kit/solver.hpp time_step).
    if (given.h_s > 0.0) run.settings.h_s = given.h_s;
    if (const std::string bad = run.solver->check(run.settings); !bad.empty())
      fail(given.h_s > 0.0 && bad.rfind("h_s", 0) == 0 ? "h_s" : given.k_contact > 0.0 && bad.rfind("stiffness", 0) == 0 ? "k_contact" : "settings",
           clip(bad, kMaxEchoedReason));
  }
}

}  // namespace pb
