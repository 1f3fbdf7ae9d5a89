#include "solvers/siconos/buildings.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "cases/text.hpp"
#include "kit/buildings_step_end.hpp"
#include "kit/fixed_step.hpp"
#include "kit/run_limits.hpp"
#include "solvers/siconos/buildings_engine.hpp"
#include "solvers/siconos/siconos_solver.hpp"

namespace pb::siconos {

// Named, not anonymous: a unity build puts this file beside the single oscillators' runs.
namespace floors {

namespace {

using buildings::BuildingsResult;

// a_g in the pulse's units, sampled at step ends as moreau-jean's end-samples samples it
// (LoadCursor::sample: Pulse::sample for the paper's pulses, a record's or a model's own).
class SceneLoad : public engine::GroundSampler {
 public:
  SceneLoad(const BuildingModel& md, double h)
      : pulse_(md.scene.pulse), cursor_(pulse_), time_(1.0 / md.w_p), accel_(md.a_p), h_(h) {}
  double operator()(double t) override { return cursor_.sample(t * time_, h_) / accel_; }

 private:
  Pulse pulse_;  // a copy, so that the sampler outlives nothing it reads
  LoadCursor cursor_;
  double time_, accel_, h_;
};

// The scene for engine.hpp, in the pulse's units (lengths over a_p / w_p^2, times over 1 / w_p).
engine::BuildingsSpec spec_of(const BuildingModel& md, double h, double t_end) {
  const double time = 1.0 / md.w_p;
  engine::BuildingsSpec spec;
  for (std::size_t b = 0; b < md.scene.buildings.size(); ++b) {
    const int n = md.scene.buildings[b].floors(), first = md.first[b];
    engine::BuildingSpec s;
    s.floors = n;
    for (int i = 0; i < n; ++i) {
      s.m.push_back(md.m(first + i));
      for (int j = 0; j < n; ++j) {
        s.k.push_back(md.K(first + i, first + j) * time * time);
        s.c.push_back(md.C(first + i, first + j) * time);
      }
    }
    spec.buildings.push_back(std::move(s));
  }
  for (const FloorContact& fc : md.contacts)
    spec.contacts.push_back({fc.left, fc.right, fc.i_left - md.first[static_cast<std::size_t>(fc.left)],
                             fc.i_right - md.first[static_cast<std::size_t>(fc.right)]});
  spec.delta = md.scene.delta / md.length_scale();
  spec.eps = md.scene.eps;
  spec.sampler = std::make_shared<SceneLoad>(md, h);
  spec.t_end = t_end / time;
  return spec;
}

// The n steps of h through Siconos, read at every step end into peaks; the status and message
// of a run that stopped early go into r, its steps into r.events.
void run(const BuildingModel& md, double h, long n, bool enumeration, const Settings& set, BuildingsResult& r,
         buildings::FloorPeaks& peaks) {
  const double time = 1.0 / md.w_p, length = md.length_scale(), speed = length / time;
  // Siconos' horizon half a step past the last step, so that round-off cannot drop it.
  engine::BuildingsStepper stepper(spec_of(md, h, (static_cast<double>(n) + 0.5) * h), h / time, set.theta, set.gamma,
                                   enumeration);
  const auto nf = static_cast<std::size_t>(md.n_floors), nc = md.contacts.size();
  std::vector<double> u(nf, 0.0), v(nf, 0.0);
  std::vector<char> was_active(nc, 0);
  const double plastic = kRestitutionFloor * md.speed_scale();
  peaks.sample(0.0, u.data());
  Deadline deadline(set);
  long k = 0;
  const auto where = [&] { return " at step " + std::to_string(k) + " (t = " + format_number(static_cast<double>(k) * h) + ")"; };
  for (; k < n; ++k) {
    // The index set of this step, chosen by Siconos from the state at t_k: a contact that
    // enters it approaching faster than the plastic speed is an impact, as moreau-jean's.
    for (std::size_t j = 0; j < nc; ++j) {
      const bool active = stepper.active(static_cast<int>(j));
      const FloorContact& fc = md.contacts[j];
      const double rate = v[static_cast<std::size_t>(fc.i_right)] - v[static_cast<std::size_t>(fc.i_left)];
      if (active && !was_active[j] && -rate > plastic) peaks.impact(j, static_cast<double>(k + 1) * h, -rate);
      was_active[j] = active ? 1 : 0;
    }
    if (!stepper.step()) {
      r.status = Status::failed;
      r.message = "Siconos ended the run" + where() + " of " + std::to_string(n);
      break;
    }
    stepper.state(u.data(), v.data());
    for (std::size_t i = 0; i < nf; ++i) {
      u[i] *= length;
      v[i] *= speed;
    }
    if (stepper.lcp_info() != 0) {
      ++k;
      r.status = Status::failed;
      r.message = "Siconos' LCP solver returned info " + std::to_string(stepper.lcp_info()) + where();
      break;
    }
    if (!buildings::end_step(md, k, n, h, u.data(), v.data(), peaks, &deadline, r)) {
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
  const std::string variant = settings.variant.empty() ? std::string(kDefaultVariant) : settings.variant;
  const bool enumeration = variant == "moreau-jean-enum";
  if (variant != "moreau-jean-lemke" && !enumeration)
    return buildings::failed("siconos on the buildings scene: variant " + variant +
                           " is not run (it takes moreau-jean-lemke and moreau-jean-enum, TimeStepping with MoreauJeanOSI)");
  if (enumeration && model.contacts.size() > static_cast<std::size_t>(kMaxEnumerationContacts))
    return buildings::failed("siconos on the buildings scene: moreau-jean-enum tries up to 2^n active sets, n = " +
                           std::to_string(model.contacts.size()) + " contacts here; it takes up to " +
                           std::to_string(kMaxEnumerationContacts) + " (moreau-jean-lemke takes any)");
  buildings::BuildingsResult r;
  long n = 0;
  if (!buildings::plan_steps(model, settings, kDefaultSteps, r, n)) return r;
  buildings::FloorPeaks peaks(model);
  try {
    floors::run(model, r.step, n, enumeration, settings, r, peaks);
  } catch (const std::exception& e) {
    r.status = Status::failed;
    r.message = std::string("Siconos: ") + e.what();
  }
  peaks.into(r);
  return r;
}

}  // namespace pb::siconos
