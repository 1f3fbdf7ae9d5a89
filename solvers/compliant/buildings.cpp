#include "solvers/compliant/buildings.hpp"

#include <algorithm>
#include <exception>
#include <span>
#include <string>

#include "kit/settings_fields.hpp"
#include "solvers/compliant/compliant.hpp"

namespace pb::compliant {

namespace {

buildings::BuildingsResult refused(const BuildingModel& md, std::string why) {
  buildings::BuildingsResult r;
  r.status = Status::failed;
  r.message = std::move(why);
  r.t_end = md.t_end;
  return r;
}

// A setting given (other than its default) that the buildings solve does not read: the
// front end refuses its flag (SolverInfo::buildings_settings); a caller of this function
// directly is told the same. "" when there is none.
std::string unread_setting(const Settings& settings) {
  static const Settings defaults;
  const auto read = std::span<const std::string_view>(kBuildingsSettings);
  for (const SettingField& f : kSettingFields) {
    if (std::find(read.begin(), read.end(), f.name) != read.end()) continue;
    const bool given = f.text ? settings.*f.text != defaults.*f.text : !(f.get(settings) == f.get(defaults));
    if (given) return std::string(f.name) + ": not used by compliant on the buildings scene";
  }
  return {};
}

}  // namespace

buildings::BuildingsResult solve_buildings(const BuildingModel& md, const Settings& settings) {
  if (std::string bad = check_limits(settings); !bad.empty()) return refused(md, bad);
  if (std::string bad = check(settings); !bad.empty()) return refused(md, bad);
  if (std::string bad = unread_setting(settings); !bad.empty()) return refused(md, bad);
  const Model element = *parse_model(settings.variant);
  if (std::string_view bad = eps_problem(element, md.scene.eps); !bad.empty())
    return refused(md, "eps: " + std::string(bad));
  const Pulse& pulse = md.scene.pulse;
  if (element != Model::kelvin_voigt && pulse.record && !(pulse.record->length_scale() > 0.0))
    return refused(md, "record: its Fourier amplitudes vanish between 0.25 and 20 Hz, so it has no mean period to "
                       "give a Hertz-type element its length scale (cases/README.md)");
  const double K = settings.stiffness > 0.0 ? settings.stiffness : kDefaultStiffness;
  try {
    if (settings.integrator == "newmark") return run_buildings_newmark(md, settings, element, K);
    return run_buildings_cvode(md, settings, element, K, settings.method == "adams");
  } catch (const std::exception& e) {
    return refused(md, e.what());
  }
}

}  // namespace pb::compliant
