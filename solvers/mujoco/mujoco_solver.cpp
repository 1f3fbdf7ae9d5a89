#include "solvers/mujoco/mujoco_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "kit/fixed_step.hpp"
#include "solvers/mujoco/model.hpp"
#include "kit/variant_table.hpp"
#include "kit/whole_contacts.hpp"

namespace pb::mujoco {

namespace {

// The geom of each body's sphere is the right end of at most one contact: its index, or -1.
std::vector<int> contacts_by_geom(const System& sys, const mjModel* m) {
  std::vector<int> out(ix(m->ngeom), -1);
  for (int j = 0; j < sys.n_contacts(); ++j) {
    const int g = mj_name2id(m, mjOBJ_GEOM, ("g" + std::to_string(sys.right(j))).c_str());
    if (g >= 0) out[ix(g)] = j;
  }
  return out;
}

// MuJoCo behind the shared step loop (kit/fixed_step.hpp).
class Engine : public StepEngine {
 public:
  Engine(const System& sys, const Config& config, const Units& units, double h_model, ModelPtr model, DataPtr data)
      : StepEngine(sys),
        sys_(sys),
        units_(units),
        h_model_(h_model),
        model_(std::move(model)),
        data_(std::move(data)),
        geoms_(contacts_by_geom(sys, model_.get())),
        load_(sys, units, geoms_, config.integrator == Integrator::rk4 ? 4 : 1),
        contacts_(sys),
        touched_(ix(sys.n_contacts()), 0) {
    for (int i = 0; i < sys.n_bodies(); ++i) {
      data_->qpos[i] = out_.u[ix(i)] / units_.length;
      data_->qvel[i] = out_.v[ix(i)] * units_.time / units_.length;
    }
  }

  StepOutcome step(long k, Result& res) override {
    mjData* d = data_.get();
    load_.begin_step();
    // The step's start time from its index, not from MuJoCo's running sum of h.
    d->time = static_cast<double>(k) * h_model_;
    {
      LoadScope scope(load_);
      mj_step(model_.get(), d);
    }
    if (!load_.end_step(d)) {
      res.status = Status::failed;
      res.message = "MuJoCo evaluated the dynamics an unexpected number of times in step " + std::to_string(k + 1);
      return StepOutcome::refused;
    }
    // MuJoCo resets the state (to rest) when qpos, qvel or qacc is NaN, infinite or above
    // 1e10 in size: the step's outcome is then not the motion.
    for (int w : {mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC})
      if (d->warning[w].number > 0) {
        res.status = Status::nan;
        res.message = "MuJoCo found a NaN, inf or |value| > 1e10 in its state and reset it";
        return StepOutcome::taken_then_stop;
      }
    const double force_unit = units_.length / (units_.time * units_.time);
    for (int j = 0; j < sys_.n_contacts(); ++j) {
      const bool touched = load_.force(j) > 0.0;  // pushed in the step: a contact ends when its force does
      contacts_.step(j, touched, out_.v.data());  // the velocities at the step's start
      out_.entered[ix(j)] = touched && !touched_[ix(j)] ? 1 : 0;
      out_.force[ix(j)] = load_.force(j) * force_unit;
      touched_[ix(j)] = touched;
    }
    for (int i = 0; i < sys_.n_bodies(); ++i) {
      out_.u[ix(i)] = d->qpos[i] * units_.length;
      out_.v[ix(i)] = d->qvel[i] * units_.length / units_.time;
    }
    return StepOutcome::taken;
  }

  void finish(Result& res) override {
    contacts_.finish(res);
    if (const Warnings w = take_warnings(); w.count > 0) {
      if (!res.message.empty()) res.message += "; ";
      res.message += "MuJoCo warned " + std::to_string(w.count) + " times (first: " + w.first + ")";
    }
  }

 private:
  const System& sys_;
  Units units_;
  double h_model_;
  ModelPtr model_;
  DataPtr data_;
  std::vector<int> geoms_;
  Load load_;
  WholeContacts contacts_;
  std::vector<char> touched_;  // per contact: MuJoCo reported it in the last step
};

std::string check_bodies(const System& sys) {
  for (const Body& b : sys.bodies)
    if (!(b.m > 0.0 && std::isfinite(b.m)) || !std::isfinite(b.k) || !std::isfinite(b.c))
      return "every body needs a finite positive mass and a finite stiffness and damping";
  return {};
}

Result run(const System& sys, const Settings& set, const Config& config) {
  if (std::string bad = check_bodies(sys); !bad.empty()) return failed(bad);
  StepPlan plan;
  if (Result r = plan_steps(sys, set, kDefaultSteps, kDefaultStepCap, plan); r.status != Status::ok) return r;
  prepare_process();
  const Units units = units_of(sys, config);
  const double h_model = plan.h / units.time;
  std::optional<ContactParameters> contact;
  if (config.calibrated) contact = calibrated_contact(sys.eps, contact_steps(set), h_model);
  std::string error;
  ModelPtr model = compile(scene_xml(sys, config, units, h_model, contact ? &*contact : nullptr), error);
  if (!model) return failed("MuJoCo could not compile the model: " + error);
  DataPtr data(mj_makeData(model.get()));
  if (!data) return failed("MuJoCo could not make its data");
  (void)take_warnings();  // only this run's steps count
  Engine engine(sys, config, units, h_model, std::move(model), std::move(data));
  Result res = run_steps(sys, set, plan, engine);
  return res;
}

}  // namespace

Result solve(const System& system, const Settings& settings) {
  return solve_linear_variant(kVariants, system, settings,
                              "mujoco's slide joints own the bodies' springs (a linear joint stiffness); "
                              "the bilinear law is not applied",
                              &run);
}

std::string describe(const Settings& settings) {
  return describe_variant(kVariants, settings, kDefaultSteps);
}

std::string check(const Settings& settings) {
  if (std::string bad = check_variant("mujoco", kVariants, settings, kDefaultSteps); !bad.empty()) return bad;
  const double m = settings.contact_steps;
  if (!(m == 0.0 || (m >= kMinContactSteps && m <= kMaxContactSteps)))
    return "contact_steps: must be in [1, 1e6] (0: the default 2)";
  return {};
}

}  // namespace pb::mujoco
