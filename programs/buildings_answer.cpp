// The buildings scene's answer (programs/buildings_protocol.hpp), read into a BuildingsResult
// with every error naming its field, as the single oscillators' answer is read
// (programs/protocol.cpp, fill_answer): the same parse (no key twice, 16 levels at most, the
// time limit), the same status and message rules.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cases/text.hpp"
#include "programs/buildings_protocol.hpp"
#include "programs/json_reading.hpp"

namespace pb::programs {

namespace buildings_answer {

using namespace reading;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

constexpr std::array<std::string_view, 13> kAnswerKeys = {
    "protocol", "version", "status", "message", "floor_peak", "floor_peak_time", "drift_peak", "drift_peak_time",
    "contacts", "steps", "step", "min_gap", "solve_seconds"};
constexpr std::array<std::string_view, 7> kContactKeys = {"left", "right", "floor", "impacts", "contact_phases",
                                                          "impact_velocity_max", "first_impact"};

// The times of the run: 0 to t_end, and a time-stepper's last step may end past t_end by up to
// a step (as the single oscillators' answers).
struct RunTimes {
  double last = 0.0;
  bool in(double t) const { return t >= 0.0 && t <= last; }
};

// A number of the answer that is a time of the run, or null (NaN).
double time_or_null(const Json& j, const std::string& field, const RunTimes& run) {
  if (j.is_null()) return kNaN;
  const double t = number(j, field);
  if (!run.in(t)) bad(field, "must be within the run, 0 to t_end (it is " + format_number(t) + ")");
  return t;
}

// doc[key] as one array per building of one number per floor (storey): peaks >= 0, or times of
// the run (null allowed). Absent or null: empty.
std::vector<std::vector<double>> per_floor(const Json& doc, const std::string& key, const BuildingModel& model,
                                           bool times, const RunTimes& run) {
  const auto it = doc.find(key);
  if (it == doc.end() || it->is_null()) return {};
  const std::vector<Building>& buildings = model.scene.buildings;
  if (!it->is_array() || it->size() != buildings.size())
    bad(key, "must be an array of " + std::to_string(buildings.size()) + " arrays, one per building left to right");
  std::vector<std::vector<double>> out(buildings.size());
  for (std::size_t b = 0; b < buildings.size(); ++b) {
    const Json& floors = (*it)[b];
    const std::string field = key + "[" + std::to_string(b) + "]";
    const auto n = static_cast<std::size_t>(buildings[b].floors());
    if (!floors.is_array() || floors.size() != n)
      bad(field, "must be an array of " + std::to_string(n) + " numbers, floor (storey) 1 first");
    out[b].reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::string at = field + "[" + std::to_string(i) + "]";
      if (times) {
        out[b].push_back(time_or_null(floors[i], at, run));
      } else {
        const double peak = number(floors[i], at);
        if (!(peak >= 0.0)) bad(at, "must be a peak |u| >= 0 (m)");
        out[b].push_back(peak);
      }
    }
  }
  return out;
}

// The contacts, in the case's order; with the contacts' left, right and floor where the answer
// leaves them out (it may repeat them: then they must be the case's).
std::vector<buildings::ContactResult> read_contacts(const Json& doc, const BuildingModel& model, const RunTimes& run,
                                                    bool required) {
  std::vector<buildings::ContactResult> out;
  out.reserve(model.contacts.size());
  for (const FloorContact& c : model.contacts) {
    buildings::ContactResult r;
    r.left = c.left, r.right = c.right, r.floor = c.floor;
    out.push_back(r);
  }
  const auto it = doc.find("contacts");
  if (it == doc.end() || it->is_null()) {
    if (required && !model.contacts.empty())
      bad("contacts", "status ok needs one object per contact of the case (its impacts)");
    return out;
  }
  if (!it->is_array() || it->size() != model.contacts.size())
    bad("contacts", "must be an array of " + std::to_string(model.contacts.size()) + " objects, one per contact of the case, in its order");
  for (std::size_t k = 0; k < out.size(); ++k) {
    const Json& c = (*it)[k];
    const std::string field = "contacts[" + std::to_string(k) + "]";
    if (!c.is_object()) bad(field, "must be an object");
    for (const auto& [key, value] : c.items())
      if (std::find(kContactKeys.begin(), kContactKeys.end(), key) == kContactKeys.end())
        bad(field + "." + clip(key), "unknown key (docs/external.md lists a buildings answer's keys)");
    buildings::ContactResult& r = out[k];
    const std::array<std::pair<const char*, int>, 3> names = {{{"left", r.left}, {"right", r.right}, {"floor", r.floor}}};
    for (const auto& [key, expected] : names)
      if (const auto v = c.find(key); v != c.end() && !v->is_null() && *v != expected)
        bad(field + "." + key, "must be the case's, " + std::to_string(expected) + " (contacts in the case's order)");
    if (const auto v = c.find("impacts"); v != c.end() && !v->is_null()) r.impacts = whole(*v, field + ".impacts");
    if (const auto v = c.find("contact_phases"); v != c.end() && !v->is_null())
      r.contact_phases = whole(*v, field + ".contact_phases");
    if (const auto v = maybe_number(c, "impact_velocity_max")) {
      if (!(*v >= 0.0)) bad(field + ".impact_velocity_max", "must be an approach speed >= 0 (m/s)");
      r.impact_velocity_max = *v;
    }
    if (const auto v = c.find("first_impact"); v != c.end()) r.first_impact = time_or_null(*v, field + ".first_impact", run);
  }
  return out;
}

void fill(const Json& doc, const BuildingModel& model, buildings::BuildingsResult& r) {
  for (const auto& [key, value] : doc.items())
    if (std::find(kAnswerKeys.begin(), kAnswerKeys.end(), key) == kAnswerKeys.end())
      bad(clip(key), "unknown key (docs/external.md lists a buildings answer's keys)");
  check_version(doc);
  const Json& status = member(doc, "status", "status");
  const std::optional<Status> parsed = status.is_string() ? parse_status(status.get<std::string>()) : std::nullopt;
  if (!parsed || *parsed == Status::penetration || *parsed == Status::energy)
    bad("status", "must be one of ok, diverged, nan, step_cap, time-limit, failed (it is " + clip(status.dump()) + ")");
  r.status = *parsed;
  if (const auto it = doc.find("message"); it != doc.end() && !it->is_null()) {
    if (!it->is_string()) bad("message", "must be a string");
    r.message = it->get<std::string>();
    if (r.message.size() > kMaxMessageBytes)
      bad("message", std::to_string(r.message.size()) + " bytes, more than " + std::to_string(kMaxMessageBytes) +
                         " (a message is shown in a row: put long output on stderr)");
  }
  if (const auto step = maybe_number(doc, "step")) {
    if (!(*step > 0.0 && *step <= model.t_end)) bad("step", "must be > 0 and at most t_end (a step of the run)");
    r.step = *step;
  }
  if (const auto it = doc.find("steps"); it != doc.end() && !it->is_null()) r.events = whole(*it, "steps");
  if (const auto gap = maybe_number(doc, "min_gap")) r.min_gap = *gap;
  if (const auto spent = maybe_number(doc, "solve_seconds"); spent && !(*spent >= 0.0))
    bad("solve_seconds", "must be a number of seconds >= 0");
  const RunTimes run{model.t_end + (std::isfinite(r.step) ? r.step : 0.0) + 1e-9 * model.t_end};
  const bool ok = r.status == Status::ok;
  r.floor_peak = per_floor(doc, "floor_peak", model, false, run);
  r.floor_peak_time = per_floor(doc, "floor_peak_time", model, true, run);
  r.drift_peak = per_floor(doc, "drift_peak", model, false, run);
  r.drift_peak_time = per_floor(doc, "drift_peak_time", model, true, run);
  r.contacts = read_contacts(doc, model, run, ok);
  if (ok && r.floor_peak.empty()) bad("floor_peak", "status ok needs the peak |u| of every floor (m)");
  if (ok && r.drift_peak.empty()) bad("drift_peak", "status ok needs the peak drift of every storey (m)");
  // A run that did not end ok has no peaks, whatever the program says (as Pi1 of the oscillators).
  if (!ok) r.floor_peak.clear(), r.floor_peak_time.clear(), r.drift_peak.clear(), r.drift_peak_time.clear();
  // Times where the answer gives none: NaN, shaped as the peaks (a row reads them by floor).
  for (auto [peaks, times] : {std::pair{&r.floor_peak, &r.floor_peak_time}, std::pair{&r.drift_peak, &r.drift_peak_time}})
    if (times->empty()) {
      times->resize(peaks->size());
      for (std::size_t b = 0; b < peaks->size(); ++b) (*times)[b].assign((*peaks)[b].size(), kNaN);
    }
}

}  // namespace buildings_answer

std::string read_buildings_answer(std::string_view text, const BuildingModel& model, buildings::BuildingsResult& result,
                                  std::chrono::steady_clock::time_point deadline) {
  using namespace buildings_answer;
  buildings::BuildingsResult r;
  r.step = result.step;  // the step sent, unless the answer says otherwise
  r.t_end = model.t_end;
  try {
    fill(parse_object(text, "stdout", deadline), model, r);
  } catch (const std::invalid_argument& e) {
    return std::string("answer: ") + e.what();
  } catch (const Json::exception& e) {  // a type the reader did not foresee
    return "answer: " + clip(e.what(), kMaxEchoedReason);
  }
  result = std::move(r);
  return {};
}

}  // namespace pb::programs
