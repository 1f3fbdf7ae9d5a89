#include "frontend/buildings_run.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>
#include <numbers>

#include "cases/fields.hpp"
#include "cases/text.hpp"
#include "frontend/errors.hpp"
#include "kit/settings_fields.hpp"
#include "solvers/registry.hpp"
#include "studies/physical_settings.hpp"
#include "sweep/buildings_sweep.hpp"

namespace pb::app {

namespace {

// A number, or null where it is not finite (JSON has no spelling for NaN).
nlohmann::ordered_json json_number(double x) { return std::isfinite(x) ? nlohmann::ordered_json(x) : nullptr; }

// Per building, per floor: the values times `scale`.
nlohmann::ordered_json per_floor(const std::vector<std::vector<double>>& values, double scale) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& building : values) {
    nlohmann::ordered_json floors = nlohmann::ordered_json::array();
    for (double x : building) floors.push_back(json_number(x * scale));
    out.push_back(std::move(floors));
  }
  return out;
}

std::string summary_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

// The separation of the contact between building `left` and its right neighbour at `floor`.
const FloorSeparation* separation_of(const BuildingsPoint& p, int left, int floor) {
  for (const FloorSeparation& s : p.separation)
    if (s.left == left && s.floor == floor) return &s;
  return nullptr;
}

// The separation keys of one contact (kit/separation.hpp): in m, and over a_p / w_p^2 for a
// case in Pi terms; null where the no-contact solve did not finish.
void separation_json(nlohmann::ordered_json& o, const FloorSeparation* s, bool pi_terms, double length) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::pair<const char*, double> values[] = {
      {"separation", s ? s->required : nan},       {"separation_reversed", s ? s->reversed : nan},
      {"separation_abs", s ? s->rules.abs : nan},  {"separation_srss", s ? s->rules.srss : nan},
      {"separation_ddc", s ? s->rules.ddc : nan}};
  for (const auto& [key, x] : values) o[std::string(key) + "_m"] = json_number(x);
  if (pi_terms)
    for (const auto& [key, x] : values) o[std::string(key) + "_pi"] = json_number(x / length);
}

std::string storey_counts(const BuildingScene& s) {
  std::string out;
  for (const Building& b : s.buildings) out += (out.empty() ? "" : " + ") + std::to_string(b.floors());
  return out;
}

}  // namespace

const SolverInfo& check_buildings_solver(const SolverFlags& flags, const GivenSolverFlag& given) {
  const SolverInfo* info = find_solver(flags.solver);
  if (!info || !info->solve_buildings) {
    std::string those;
    for (const SolverInfo& s : solvers())
      if (s.solve_buildings) those += (those.empty() ? "" : ", ") + std::string(s.name);
    throw BadInput("--solver: " + clip(flags.solver) + " does not solve the buildings scene (these do: " + those + ")");
  }
  if (const std::string why = info->check(flags.settings); !why.empty()) throw BadInput("--" + why);
  if (!given) return *info;
  const auto& read = info->buildings_settings;
  for (const SettingField& f : kSettingFields) {
    const std::string flag = flag_of(f.name);
    if (std::find(read.begin(), read.end(), f.name) == read.end() && given(flag)) {
      std::string flags_read;
      for (std::string_view r : read) flags_read += (flags_read.empty() ? "" : ", ") + flag_of(r);
      throw BadInput(flag + ": not used by " + std::string(info->name) + " on the buildings scene (it reads " + flags_read + ")");
    }
  }
  return *info;
}

void apply_buildings_k_contact(const BuildingScene& scene, SolverFlags& flags, double k, bool stiffness_given) {
  if (stiffness_given) throw BadInput("--k-contact: not with --stiffness (give the stiffness one way)");
  if (!(std::isfinite(k) && k > 0.0)) throw BadInput("--k-contact: must be finite and > 0");
  const SolverInfo* info = find_solver(flags.solver);
  const auto& read = info ? info->buildings_settings : std::span<const std::string_view>{};
  if (info && info->solve_buildings && std::find(read.begin(), read.end(), "stiffness") == read.end())
    throw BadInput("--k-contact: not used by " + std::string(info->name) + " on the buildings scene (it has no contact element)");
  if (!info || !info->solve_buildings) return;  // check_buildings_solver names it
  flags.settings.stiffness = k / contact_element_stiffness(assemble(scene), hertz_contact(*info, flags.settings));
}

BuildingsRun run_buildings(const ChosenCase& chosen, const SolverInfo& solver, const Settings& settings) {
  BuildingsRun run;
  run.chosen = chosen;
  run.solver = &solver;
  run.point = solve_buildings_point(chosen.building->scene, solver, settings);
  return run;
}

nlohmann::ordered_json buildings_json(const BuildingsRun& run) {
  const BuildingCase& c = *run.chosen.building;
  const buildings::BuildingsResult& r = run.point.result;
  const double length = run.point.a_p / (run.point.w_p * run.point.w_p), speed = run.point.a_p / run.point.w_p;
  nlohmann::ordered_json j;
  j["scene"] = std::string(kBuildingsScene);
  j["family"] = c.family;
  j["case_file"] = run.chosen.case_file;
  j["point"] = run.chosen.point;
  j["solver"] = std::string(run.solver->name);
  if (std::isfinite(r.step)) j["step_s"] = r.step;
  j["status"] = std::string(name(r.status));
  j["message"] = r.message;
  j["floor_peak_m"] = per_floor(r.floor_peak, 1.0);
  j["drift_peak_m"] = per_floor(r.drift_peak, 1.0);
  j["floor_peak_no_contact_m"] = per_floor(run.point.no_contact.floor_peak, 1.0);
  j["drift_peak_no_contact_m"] = per_floor(run.point.no_contact.drift_peak, 1.0);
  if (c.pi_terms) {
    j["floor_peak_pi"] = per_floor(r.floor_peak, 1.0 / length);
    j["drift_peak_pi"] = per_floor(r.drift_peak, 1.0 / length);
    j["floor_peak_no_contact_pi"] = per_floor(run.point.no_contact.floor_peak, 1.0 / length);
    j["drift_peak_no_contact_pi"] = per_floor(run.point.no_contact.drift_peak, 1.0 / length);
  }
  nlohmann::ordered_json contacts = nlohmann::ordered_json::array();
  for (const buildings::ContactResult& k : r.contacts) {
    nlohmann::ordered_json o;
    o["left"] = k.left;
    o["right"] = k.right;
    o["floor"] = k.floor;
    o["impacts"] = k.impacts;
    o["contact_phases"] = k.contact_phases;
    o["impact_velocity_max_m_s"] = json_number(k.impact_velocity_max);
    if (c.pi_terms) o["impact_velocity_max_pi"] = json_number(k.impact_velocity_max / speed);
    o["first_impact_s"] = json_number(k.first_impact);
    separation_json(o, separation_of(run.point, k.left, k.floor), c.pi_terms, length);
    contacts.push_back(std::move(o));
  }
  j["contacts"] = std::move(contacts);
  j["events"] = r.events;
  j["energy_error"] = json_number(r.energy_error);
  j["t_end_s"] = json_number(r.t_end);
  j["a_p"] = run.point.a_p;
  j["w_p"] = run.point.w_p;
  j["seconds"] = run.point.seconds;
  j["cpu_seconds"] = run.point.cpu_seconds;
  return j;
}

void print_buildings_summary(std::ostream& out, const BuildingsRun& run) {
  const BuildingCase& c = *run.chosen.building;
  const BuildingScene& s = c.scene;
  const buildings::BuildingsResult& r = run.point.result;
  out << "buildings " << storey_counts(s) << " storeys, " << (s.damping == BuildingDamping::modal ? "modal" : "rayleigh")
      << " xi " << summary_number(s.xi) << ", gap " << summary_number(s.delta) << " m, eps " << summary_number(s.eps);
  if (c.pi_terms)
    out << "  (Pi terms: pi2 " << summary_number(c.pi2) << ", pi3 " << summary_number(c.pi3) << ", pi5 " << summary_number(c.pi5) << ", pi6 "
        << summary_number(c.pi6) << ")";
  out << '\n';
  out << "load     " << name(c.pulse) << ' ' << name(c.directivity) << (c.record.empty() ? "" : " " + c.record)
      << ", a_p " << summary_number(run.point.a_p) << " m/s^2, w_p " << summary_number(run.point.w_p)
      << " rad/s, t_end " << summary_number(r.t_end) << " s\n";
  out << "solver   " << run.solver->name;
  if (run.solver->reference) out << " (exact, event-driven)";
  if (std::isfinite(r.step)) out << ", step " << summary_number(r.step) << " s";
  out << '\n';
  out << "status   " << name(r.status) << (r.message.empty() ? "" : ": " + r.message) << '\n';
  for (std::size_t b = 0; b < r.floor_peak.size(); ++b) {
    out << "building " << b << "  floor: peak |u| m, storey below: peak |drift| m (without contact in brackets)\n";
    const buildings::BuildingsResult& free = run.point.no_contact;
    const auto apart = [&](const std::vector<std::vector<double>>& v, std::size_t i) {
      return b < v.size() && i < v[b].size() ? " (" + summary_number(v[b][i]) + ")" : std::string();
    };
    for (std::size_t i = 0; i < r.floor_peak[b].size(); ++i)
      out << "  floor " << i + 1 << "  " << summary_number(r.floor_peak[b][i]) << apart(free.floor_peak, i) << "   storey "
          << i + 1 << "  " << summary_number(r.drift_peak[b][i]) << apart(free.drift_peak, i) << '\n';
  }
  for (const buildings::ContactResult& k : r.contacts) {
    out << "contact  buildings " << k.left << '-' << k.right << " floor " << k.floor << ": " << k.impacts << " impacts";
    if (std::isfinite(k.first_impact))
      out << ", first at " << summary_number(k.first_impact) << " s, fastest approach " << summary_number(k.impact_velocity_max) << " m/s";
    if (k.contact_phases > 0) out << ", " << k.contact_phases << " contact phases";
    out << '\n';
    if (const FloorSeparation* sep = separation_of(run.point, k.left, k.floor))
      out << "         gap that avoids pounding " << summary_number(sep->required) << " m (load reversed "
          << summary_number(sep->reversed) << " m); rules ABS " << summary_number(sep->rules.abs) << ", SRSS "
          << summary_number(sep->rules.srss) << " (EC8 0.7 SRSS " << summary_number(0.7 * sep->rules.srss) << "), DDC "
          << summary_number(sep->rules.ddc) << " m\n";
  }
  out << (run.solver->reference ? "events   " : "steps    ") << r.events;
  if (std::isfinite(r.energy_error)) out << ", energy error " << summary_number(r.energy_error);
  out << '\n';
  out << "time     " << summary_number(run.point.seconds) << " s\n";
}

}  // namespace pb::app
