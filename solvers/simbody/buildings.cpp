#include "solvers/simbody/buildings.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cases/text.hpp"
#include "kit/buildings_step_end.hpp"
#include "kit/fixed_step.hpp"
#include "kit/run_limits.hpp"
#include "solvers/simbody/model.hpp"
#include "solvers/simbody/simbody_solver.hpp"
#include "solvers/simbody/variants.hpp"

namespace pb::simbody {

// Named, not anonymous: a unity build puts this file beside the single oscillators' runs.
namespace floors {

namespace {

using buildings::BuildingsResult;

// The model's units: the pulse's length a_p / w_p^2, time 1 / w_p, building 0's floor 1's mass.
struct Units {
  double length, time, mass;
  explicit Units(const BuildingModel& md) : length(md.length_scale()), time(1.0 / md.w_p), mass(md.m(0)) {}
  double velocity() const { return length / time; }
};

ModelSpec model_spec(const BuildingModel& md, const Config& config, const Settings& set, double h, const Units& un) {
  ModelSpec spec;
  spec.kind = config.kind;
  const int n = md.n_floors;
  const bool rayleigh = md.scene.damping == BuildingDamping::rayleigh;
  std::vector<double> a0(md.scene.buildings.size(), 0.0), a1(a0.size(), 0.0);
  if (rayleigh)
    for (std::size_t b = 0; b < a0.size(); ++b) {
      const BuildingModes& modes = md.modes[b];
      rayleigh_coefficients(md.scene.xi, modes.w(0), modes.w.size() > 1 ? modes.w(1) : modes.w(0), a0[b], a1[b]);
    }
  for (int i = 0; i < n; ++i) {
    const auto b = static_cast<std::size_t>(md.building_of[static_cast<std::size_t>(i)]);
    spec.m.push_back(md.m(i) / un.mass);
    spec.k.push_back(0.0);  // the storeys' springs are links
    spec.c.push_back(a0[b] * md.m(i) * un.time / un.mass);  // Rayleigh's a0 M; 0 for modal
    spec.u.push_back(0.0);
    spec.v.push_back(0.0);
    ModelSpec::Link link;
    link.lower = i == md.first[b] ? -1 : i - 1;
    link.upper = i;
    link.k = md.k(i) * un.time * un.time / un.mass;
    link.c = a1[b] * md.k(i) * un.time / un.mass;  // Rayleigh's a1 K: a dashpot per storey
    spec.links.push_back(link);
  }
  if (!rayleigh) {
    spec.damping_matrix.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        spec.damping_matrix[static_cast<std::size_t>(i * n + j)] = md.C(i, j) * un.time / un.mass;
  }
  for (const FloorContact& fc : md.contacts) {
    spec.left.push_back(fc.i_left);
    spec.right.push_back(fc.i_right);
  }
  spec.delta = md.scene.delta / un.length;
  spec.eps = md.scene.eps;
  spec.ground_accel = [load = LoadCursor(md.scene.pulse), un](double t) mutable {
    return load.accel(t * un.time) * un.time * un.time / un.length;
  };
  spec.h = h / un.time;
  spec.gamma = set.gamma;
  spec.constraint_tol = kFaithfulConstraintTol;
  return spec;
}

// How far a run may pass its time limit inside a step that cannot be interrupted, as the single
// oscillators' (simbody_solver.cpp): a step of PLUS whose silent stretches could pass a tenth
// of the limit (half a second at least), four of them a step, is not started.
constexpr double kLimitMargin = 0.1, kLimitMarginMin = 0.5;
constexpr int kSilentPerStep = 4;

// The n steps of h through Simbody's stepper, read at every step end into peaks; the status
// and message of a run that stopped early go into r, its steps into r.events.
void run(const BuildingModel& md, double h, long n, Model& model, Deadline& deadline, const Settings& set,
         BuildingsResult& r, buildings::FloorPeaks& peaks) {
  const auto nf = static_cast<std::size_t>(md.n_floors), nc = md.contacts.size();
  const Units un(md);
  std::vector<double> u(nf, 0.0), v(nf, 0.0), rate(nc, 0.0);
  std::vector<char> engaged(nc, 0);
  const double plastic = kRestitutionFloor * md.speed_scale();
  peaks.sample(0.0, u.data());
  long k = 0;
  const auto at = [&] { return " at t = " + format_number(static_cast<double>(k) * h); };
  for (; k < n; ++k) {
    if (deadline.tick()) {
      r.status = Status::time_limit;
      r.message = deadline.reason() + at();
      break;
    }
    if (set.time_limit > 0.0 &&
        kSilentPerStep * model.silent_seconds(model.contacts_next_step()) >
            std::max(kLimitMarginMin, kLimitMargin * set.time_limit)) {
      r.status = Status::time_limit;
      r.message = "refused" + at() + ": the next step's impulse solve (Simbody's PLUS) could pass the time limit "
                  "by more than its margin where no limit can stop it";
      break;
    }
    for (std::size_t j = 0; j < nc; ++j) {
      const FloorContact& fc = md.contacts[j];
      rate[j] = v[static_cast<std::size_t>(fc.i_right)] - v[static_cast<std::size_t>(fc.i_left)];
    }
    bool done = true;
    try {
      done = model.step(k);
    } catch (const std::exception& e) {
      ++k;
      r.status = Status::failed;
      r.message = e.what() + std::string(" (step ") + std::to_string(k) + ")";
      break;
    }
    if (!done) {
      r.status = Status::time_limit;
      r.message = deadline.reason() + at() + ", inside Simbody's step " + std::to_string(k + 1);
      break;
    }
    for (std::size_t i = 0; i < nf; ++i) {
      u[i] = model.u(static_cast<int>(i)) * un.length;
      v[i] = model.v(static_cast<int>(i)) * un.velocity();
    }
    // A contact that entered the stepper's proximal set approaching faster than the plastic
    // speed at the step's start is an impact, seen at the step's end (moreau-jean's count).
    for (std::size_t j = 0; j < nc; ++j) {
      const bool on = model.contact(static_cast<int>(j)).engaged;
      if (on && !engaged[j] && -rate[j] > plastic) peaks.impact(j, static_cast<double>(k + 1) * h, -rate[j]);
      engaged[j] = on ? 1 : 0;
    }
    // Simbody's time limit is looked at before each step (deadline.tick above).
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
  const std::optional<Config> config = kVariants.find(settings.variant);
  if (config && !config->time_stepper())
    return buildings::failed("simbody on the buildings scene: variant " + std::string(config->name) +
                             " is not run (it takes plus-faithful, pgs-faithful and default, its time-stepper; "
                             "compliant elements on the buildings are the compliant solver's)");
  if (std::string why = check(settings); !why.empty()) return buildings::failed(why);
  buildings::BuildingsResult r;
  long n = 0;
  if (!buildings::plan_steps(model, settings, kDefaultSteps, r, n)) return r;
  buildings::FloorPeaks peaks(model);
  Deadline deadline(settings);  // from here: the model's set-up counts against the limit
  try {
    ModelSpec spec = floors::model_spec(model, *config, settings, r.step, floors::Units(model));
    spec.out_of_time = [&deadline] { return deadline.tick(); };
    Model sim(spec);
    floors::run(model, r.step, n, sim, deadline, settings, r, peaks);
  } catch (const std::exception& e) {
    r.status = Status::failed;
    r.message = e.what();
  }
  peaks.into(r);
  return r;
}

}  // namespace pb::simbody
