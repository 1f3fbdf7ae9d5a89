#include "rows/buildings_rows.hpp"

#include <array>
#include <cmath>
#include <limits>

#include "cases/text.hpp"
#include "rows/line_builder.hpp"

namespace pb {

namespace {

constexpr std::array kBuildingsColumns = {
    "family", "point", "pulse", "directivity", "record", "solver", "settings", "status", "message", "building",
    "floor", "floors",
    // the solver's peaks and the reference's without contact; in m, then over a_p / w_p^2
    "floor_peak_m", "drift_peak_m", "floor_peak_no_contact_m", "drift_peak_no_contact_m", "floor_peak_pi",
    "drift_peak_pi", "floor_peak_no_contact_pi", "drift_peak_no_contact_pi",
    // the contact of this floor with the right neighbour's
    "impacts_right", "impact_velocity_max_right_m_s", "first_impact_right_s",
    // the point: its scales and, for a case in Pi terms, its terms
    "gap_m", "eps", "a_p", "w_p", "pi2", "pi3", "pi5", "pi6", "t_end_s", "step_s", "seconds", "cpu_seconds",
    // the gap that avoids pounding at the contact with the right neighbour (the load as given and
    // reversed) and the rules' gaps, from the no-contact response (kit/separation.hpp)
    "separation_right_m", "separation_reversed_right_m", "separation_abs_right_m", "separation_srss_right_m",
    "separation_ddc_right_m"};

double floor_value(const std::vector<std::vector<double>>& v, std::size_t b, std::size_t i) {
  return b < v.size() && i < v[b].size() ? v[b][i] : std::numeric_limits<double>::quiet_NaN();
}

const buildings::ContactResult* contact_to_the_right(const buildings::BuildingsResult& r, std::size_t b, int floor) {
  for (const buildings::ContactResult& c : r.contacts)
    if (static_cast<std::size_t>(c.left) == b && c.floor == floor) return &c;
  return nullptr;
}

const FloorSeparation* separation_to_the_right(const BuildingsPoint& p, std::size_t b, int floor) {
  for (const FloorSeparation& s : p.separation)
    if (static_cast<std::size_t>(s.left) == b && s.floor == floor) return &s;
  return nullptr;
}

}  // namespace

std::string buildings_csv_header() {
  LineBuilder line;
  for (const char* c : kBuildingsColumns) line.text(c);
  return line.take() + '\n';
}

void append_buildings_rows(std::string& out, const BuildingCase& c, std::size_t point, std::string_view solver,
                           std::string_view settings, const BuildingsPoint& p) {
  const BuildingScene& s = c.scene;
  const double a_p = p.a_p, w_p = p.w_p, length = a_p / (w_p * w_p);
  const buildings::BuildingsResult& r = p.result;
  for (std::size_t b = 0; b < s.buildings.size(); ++b) {
    const int floors = s.buildings[b].floors();
    for (int floor = 1; floor <= floors; ++floor) {
      const auto i = static_cast<std::size_t>(floor - 1);
      LineBuilder line;
      line.text(c.family);
      line.count(static_cast<long long>(point));
      line.text(name(c.pulse));
      line.text(name(c.directivity));
      line.text(c.record);
      line.text(solver);
      line.text(settings);
      line.text(name(r.status));
      line.text(r.message);
      line.count(static_cast<long long>(b));
      line.count(floor);
      line.count(floors);
      const std::array peaks = {floor_value(r.floor_peak, b, i), floor_value(r.drift_peak, b, i), floor_value(p.no_contact.floor_peak, b, i),
                                floor_value(p.no_contact.drift_peak, b, i)};
      for (double x : peaks) line.number(x);
      for (double x : peaks) line.number(x / length);
      const buildings::ContactResult* k = contact_to_the_right(r, b, floor);
      if (k) {
        line.count(k->impacts);
        line.number(k->impact_velocity_max);
        line.number(k->first_impact);
      } else {
        for (int n = 0; n < 3; ++n) line.number(std::numeric_limits<double>::quiet_NaN());
      }
      for (double x : {s.delta, s.eps, a_p, w_p, c.pi2, c.pi3, c.pi5, c.pi6, r.t_end, r.step, p.seconds, p.cpu_seconds})
        line.number(x);
      if (const FloorSeparation* sep = separation_to_the_right(p, b, floor)) {
        for (double x : {sep->required, sep->reversed, sep->rules.abs, sep->rules.srss, sep->rules.ddc}) line.number(x);
      } else {
        for (int n = 0; n < 5; ++n) line.number(std::numeric_limits<double>::quiet_NaN());
      }
      out += line.take();
      out += '\n';
    }
  }
}

}  // namespace pb
