#include "solvers/ode/ode_solver.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <optional>

#include "kit/fixed_step.hpp"
#include "kit/hysteresis.hpp"
#include "solvers/ode/world.hpp"
#include "kit/variant_table.hpp"

namespace pb::ode {

namespace {

std::string check_config(const Config& c) {
  if (c.stepper == Stepper::quickstep && c.iterations < 1) return "iterations: must be >= 1";
  if (c.stepper == Stepper::quickstep && !(c.sor > 0.0 && c.sor < 2.0)) return "sor: must be in (0, 2)";
  if (!(c.erp >= 0.0 && c.erp <= 1.0)) return "erp: must be in [0, 1]";
  if (!(c.cfm >= 0.0)) return "cfm: must be >= 0";
  if (!(c.bounce_vel >= 0.0)) return "bounce_vel: must be >= 0";
  if (!(c.surface_layer >= 0.0)) return "surface_layer: must be >= 0";
  if (!(c.max_vel >= 0.0)) return "max_vel: must be >= 0";
  return {};
}

// ODE behind the shared step loop (kit/fixed_step.hpp): each step applies the springs,
// dashpots and ground load of its start, makes the contact joints its activation rule asks
// for from the gaps and rates there, and lets ODE step.
class Engine : public StepEngine {
 public:
  Engine(const System& sys, const Config& config, double h, double gamma)
      : StepEngine(sys), sys_(sys), load_(sys.pulse), config_(config), h_(h), gamma_h_(gamma * h), joint_(ix(sys.n_contacts()), 0),
        feedback_(ix(sys.n_contacts()), dJointFeedback{}), springs_(sys, out_.u) {}

  // False when ODE could not make the world.
  bool start() {
    if (!world_.ok()) return false;
    set_up_world();
    add_bodies();
    (void)take_messages();  // only this run's messages go into its result
    lcp_failures_before_ = lcp_failures();
    return true;
  }

  StepOutcome step(long k, Result& res) override {
    if (!apply_loads(k)) {
      res.status = Status::nan;
      res.message = "non-finite force";
      return StepOutcome::refused;
    }
    const int rows = make_contacts();
    const int stepped = config_.stepper == Stepper::quickstep ? quick_step(world_.id(), h_, rows)
                                                              : dWorldStep(world_.id(), h_);
    if (stepped == 0) {
      res.status = Status::failed;
      res.message = "ODE could not step (working memory)";
      return StepOutcome::refused;
    }
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      out_.u[i] = dBodyGetPosition(bodies_[i])[0];
      out_.v[i] = dBodyGetLinearVel(bodies_[i])[0];
    }
    for (std::size_t j = 0; j < joint_.size(); ++j) out_.force[j] = joint_[j] ? feedback_[j].f1[0] : 0.0;
    if (lcp_failures() != lcp_failures_before_) return dantzig_gave_up("ODE", k, "forces", res);
    return StepOutcome::taken;
  }

  void finish(Result& res) override {
    springs_.finish(out_.u.data(), res);
    if (res.status == Status::ok && !still_on_axis()) {
      res.status = Status::failed;
      res.message = "a body left the x axis or rotated";
    }
    if (std::string notes = take_messages(); !notes.empty())
      res.message += (res.message.empty() ? "" : "; ") + notes;
  }

 private:
  void set_up_world() {
    const dWorldID w = world_.id();
    configure_world(w, config_);
  }

  // Bodies are created right to left. ODE keeps its bodies newest first and orders the
  // rows of a step by walking them, so the contact rows reach its Dantzig solver left to
  // right. The order matters only at exact ties, which ODE's Dantzig cannot pivot through:
  // a row at w = 0 (bodies touching and moving alike) taken before the row that pushes it
  // makes a zero step, and ODE gives up on the step (README, degenerate LCPs). Left to
  // right suits the one kick of the case set, body 0 at the left end of a chain.
  void add_bodies() {
    bodies_.assign(sys_.bodies.size(), nullptr);
    for (std::size_t i = sys_.bodies.size(); i-- > 0;) {
      const double m = sys_.bodies[i].m;
      const dBodyID b = dBodyCreate(world_.id());
      dMass mass;
      // Rotational inertia of a unit radius of gyration: rotation never starts (no torque).
      dMassSetParameters(&mass, m, 0.0, 0.0, 0.0, m, m, m, 0.0, 0.0, 0.0);
      dBodySetMass(b, &mass);
      dBodySetPosition(b, out_.u[i], 0.0, 0.0);
      dBodySetLinearVel(b, out_.v[i], 0.0, 0.0);
      dBodySetAutoDisableFlag(b, 0);
      bodies_[i] = b;
    }
  }

  // Spring (a yielding body's by its return map), dashpot and ground load of each body at the
  // start of step k. Returns false
  // if a force is not finite (ODE must never see one).
  bool apply_loads(long k) {
    const double a_g = load_.accel(static_cast<double>(k) * h_);
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const Body& b = sys_.bodies[i];
      const double f = -springs_.force(static_cast<int>(i), out_.u[i], a_g) - b.c * out_.v[i] - b.m * a_g;
      if (!std::isfinite(f)) return false;
      dBodyAddForce(bodies_[i], f, 0.0, 0.0);
    }
    return true;
  }

  // The contact joints of this step, made from the state at its start. Returns their number.
  int make_contacts() {
    dJointGroupEmpty(world_.contacts());
    int made = 0;
    for (int j = 0; j < sys_.n_contacts(); ++j) {
      const auto jj = ix(j);
      const double g = sys_.gap(j, out_.u.data()), rate = sys_.gap_rate(j, out_.v.data());
      const bool make = active(config_.activation, g, rate, gamma_h_);
      out_.entered[jj] = make && !joint_[jj] ? 1 : 0;
      joint_[jj] = make ? 1 : 0;
      if (!make) continue;
      ++made;
      const dBodyID right = bodies_[ix(sys_.right(j))];
      const int left = sys_.left(j);
      dContact c{};
      c.surface.mode = dContactBounce;
      c.surface.mu = 0.0;
      c.surface.bounce = sys_.eps;
      c.surface.bounce_vel = config_.bounce_vel;
      // ODE's normal points into body 1: +x, so body 1 is the right body. The point lies on
      // the x axis, so the angular rows of the Jacobian are exactly zero.
      c.geom.pos[0] = out_.u[ix(sys_.right(j))];
      c.geom.normal[0] = 1.0;
      // A joint made ahead of time (g > 0) has depth 0: ODE's push-out term is then zero and
      // the row is the bounce alone, lambda >= 0 (never a pull across the gap).
      c.geom.depth = std::max(0.0, -g);
      const dJointID joint = dJointCreateContact(world_.id(), world_.contacts(), &c);
      dJointAttach(joint, right, left == kWall ? nullptr : bodies_[ix(left)]);
      dJointSetFeedback(joint, &feedback_[jj]);
    }
    return made;
  }

  // Every body must still be on the x axis, unrotated: the model's premise.
  bool still_on_axis() const {
    for (const dBodyID b : bodies_) {
      const dReal* p = dBodyGetPosition(b);
      const dReal* v = dBodyGetLinearVel(b);
      const dReal* w = dBodyGetAngularVel(b);
      const dReal* q = dBodyGetQuaternion(b);
      if (p[1] != 0.0 || p[2] != 0.0 || v[1] != 0.0 || v[2] != 0.0) return false;
      if (w[0] != 0.0 || w[1] != 0.0 || w[2] != 0.0) return false;
      if (q[0] != 1.0 || q[1] != 0.0 || q[2] != 0.0 || q[3] != 0.0) return false;
    }
    return true;
  }

  const System& sys_;
  LoadCursor load_;  // a_g at each step's start, O(1) on a record
  const Config& config_;
  double h_;
  double gamma_h_;  // Settings::gamma h, for the predicted rule
  World world_;
  std::vector<dBodyID> bodies_;
  std::vector<char> joint_;                // a contact joint was made for the last step
  std::vector<dJointFeedback> feedback_;   // one per contact; ODE writes it during the step
  StepSprings springs_;                    // the bodies' springs (hysteresis.hpp)
  long lcp_failures_before_ = 0;
};

Result run(const System& sys, const Settings& set, const Config& config) {
  if (std::string bad = check_config(config); !bad.empty()) return failed("config: " + bad);
  for (const Body& b : sys.bodies)
    if (!(b.m > 0.0 && std::isfinite(b.m))) return failed("every body needs a finite positive mass");
  StepPlan plan;
  if (Result r = plan_steps(sys, set, kDefaultSteps, kDefaultStepCap, plan); r.status != Status::ok) return r;
  if (!prepare_thread()) return failed("ODE could not be initialised on this thread");
  Engine engine(sys, config, plan.h, set.gamma);
  if (!engine.start()) return failed("ODE could not create a world");
  return run_steps(sys, set, plan, engine);
}

Result guarded(const System& sys, const Settings& set, const Config& config) {
  try {
    return run(sys, set, config);
  } catch (const std::exception& e) {
    return failed(e.what());
  }
}

}  // namespace

Result solve(const System& system, const Settings& settings) {
  const std::optional<Config> config = kVariants.find(settings.variant);
  if (!config) return failed("unknown variant " + settings.variant);
  return guarded(system, settings, *config);
}

Result solve_with(const System& system, const Settings& settings, const Config& config) {
  return guarded(system, settings, config);
}

std::string describe(const Settings& settings) {
  return describe_variant(kVariants, settings, kDefaultSteps);
}

std::string check(const Settings& settings) {
  return check_variant("ode", kVariants, settings, kDefaultSteps);
}

}  // namespace pb::ode
