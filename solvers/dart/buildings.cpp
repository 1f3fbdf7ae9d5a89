#include "solvers/dart/buildings.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cases/text.hpp"
#include "kit/buildings_step_end.hpp"
#include "kit/fixed_step.hpp"
#include "solvers/dart/buildings_models.hpp"
#include "solvers/dart/dart_solver.hpp"
#include "solvers/dart/variants.hpp"

namespace pb::dart {

void add_note(buildings::BuildingsResult& r, const std::string& note) {
  r.message += (r.message.empty() ? "" : "; ") + note;
}

// Named, not anonymous: a unity build puts this file beside the single oscillators' runs.
namespace floors {

namespace {

using buildings::BuildingsResult;

// The n steps of h through the engine, read at every step end into peaks; the status and
// message of a run that stopped early go into r, its steps into r.events.
void run(const BuildingModel& md, double h, long n, FloorsEngine& engine, RunLimit& limit, BuildingsResult& r,
         buildings::FloorPeaks& peaks) {
  LoadCursor load(md.scene.pulse);  // a_g at each step's start, as the single oscillators'
  const auto nc = md.contacts.size();
  std::vector<double> rate(nc, 0.0);
  const double plastic = kRestitutionFloor * md.speed_scale();
  const std::vector<double>& u = engine.u();
  const std::vector<double>& v = engine.v();
  peaks.sample(0.0, u.data());
  long k = 0;
  for (; k < n; ++k) {
    for (std::size_t j = 0; j < nc; ++j) {
      const FloorContact& fc = md.contacts[j];
      rate[j] = v[static_cast<std::size_t>(fc.i_right)] - v[static_cast<std::size_t>(fc.i_left)];
    }
    bool go_on = true;
    try {
      go_on = engine.step(k, load.accel(static_cast<double>(k) * h), r);
    } catch (const OutOfTime&) {
      r.status = Status::time_limit;
      r.message = limit.reason() + " at t = " + format_number(static_cast<double>(k) * h) + ", inside DART's step " +
                  std::to_string(k + 1);
      break;
    }
    if (!go_on) {
      ++k;
      break;
    }
    // A contact that entered the step's contact set approaching faster than the plastic speed
    // at the step's start is an impact, seen at the step's end (moreau-jean's count).
    const std::vector<char>& entered = engine.entered();
    for (std::size_t j = 0; j < nc; ++j)
      if (entered[j] && -rate[j] > plastic) peaks.impact(j, static_cast<double>(k + 1) * h, -rate[j]);
    // DART's time limit is its RunLimit's, looked at inside its step (OutOfTime above).
    if (!buildings::end_step(md, k, n, h, u.data(), v.data(), peaks, nullptr, r)) {
      ++k;
      break;
    }
  }
  r.events = k;
}

}  // namespace

}  // namespace floors

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings) {
  if (std::string why = validate(model.scene); !why.empty()) return buildings::failed(why);
  if (std::string why = check(settings); !why.empty()) return buildings::failed(why);
  const std::optional<Config> config = kVariants.find(settings.variant);
  if (!config) return buildings::failed("dart on the buildings scene: unknown variant '" + settings.variant + "'");
  buildings::BuildingsResult r;
  long n = 0;
  if (!buildings::plan_steps(model, settings, kDefaultSteps, r, n)) return r;
  buildings::FloorPeaks peaks(model);
  // The limit holds from here, through the model's set-up (run_limit.hpp).
  RunLimit limit(settings);
  try {
    const std::unique_ptr<FloorsEngine> engine = config->faithful
                                                     ? make_faithful_floors(model, *config, settings, r.step, limit)
                                                     : make_default_floors(model, r.step, limit);
    floors::run(model, r.step, n, *engine, limit, r, peaks);
    engine->finish(r);
  } catch (const OutOfTime&) {
    r.status = Status::time_limit;
    r.message = limit.reason() + " in DART's set-up of " + std::to_string(model.n_floors) + " floors";
  } catch (const std::exception& e) {
    r.status = Status::failed;
    r.message = std::string("DART: ") + e.what();
  }
  peaks.into(r);
  return r;
}

}  // namespace pb::dart
