#include "solvers/ode/buildings.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "cases/text.hpp"
#include "kit/buildings_step_end.hpp"
#include "kit/fixed_step.hpp"
#include "kit/run_limits.hpp"
#include "solvers/ode/ode_solver.hpp"
#include "solvers/ode/world.hpp"

namespace pb::ode {

// Named, not anonymous: a unity build puts this file beside the single oscillators' Engine.
namespace floors {

namespace {

using buildings::BuildingsResult;

// One run: the world, a body per floor, the contact joints of each step.
class Run {
 public:
  Run(const BuildingModel& md, const Config& config, double h, double gamma)
      : md_(md),
        config_(config),
        h_(h),
        gamma_h_(gamma * h),
        n_(md.n_floors),
        load_(md.scene.pulse),
        joint_(md.contacts.size(), 0),
        feedback_(md.contacts.size(), dJointFeedback{}),
        bodies_(static_cast<std::size_t>(n_), nullptr) {
    // [K C]: the storeys' and the dampers' forces in one sparse product per step.
    Eigen::MatrixXd both(n_, 2 * n_);
    both << md.K, md.C;
    smooth_ = both.sparseView();
    x_.setZero(2 * n_);
    f_.setZero(n_);
  }

  // False when ODE could not make the world.
  bool start() {
    if (!world_.ok()) return false;
    const dWorldID w = world_.id();
    configure_world(w, config_);
    // The floors right to left, as the single oscillators' bodies: ODE walks its bodies newest
    // first, so the contact rows reach its Dantzig solver left to right (README, degenerate LCPs).
    for (int i = n_; i-- > 0;) {
      const double m = md_.m(i);
      const dBodyID b = dBodyCreate(w);
      dMass mass;
      dMassSetParameters(&mass, m, 0.0, 0.0, 0.0, m, m, m, 0.0, 0.0, 0.0);
      dBodySetMass(b, &mass);
      dBodySetPosition(b, 0.0, 0.0, 0.0);
      dBodySetLinearVel(b, 0.0, 0.0, 0.0);
      dBodySetAutoDisableFlag(b, 0);
      bodies_[static_cast<std::size_t>(i)] = b;
    }
    (void)take_messages();  // only this run's messages go into its result
    lcp_failures_before_ = lcp_failures();
    return true;
  }

  double u(int i) const { return x_(i); }
  double v(int i) const { return x_(n_ + i); }
  const double* u_data() const { return x_.data(); }

  // -K u - C v - m a_g(t_k) on every floor at the start of step k; false if a force is not
  // finite (ODE must never see one).
  bool apply_loads(long k) {
    const double a_g = load_.accel(static_cast<double>(k) * h_);
    f_.noalias() = smooth_ * x_;
    for (int i = 0; i < n_; ++i) {
      const double f = -f_(i) - md_.m(i) * a_g;
      if (!std::isfinite(f)) return false;
      dBodyAddForce(bodies_[static_cast<std::size_t>(i)], f, 0.0, 0.0);
    }
    return true;
  }

  // The joints of step k from the state at its start; the impacts go to peaks at the step's
  // end. Returns how many joints were made.
  int make_contacts(long k, buildings::FloorPeaks& peaks) {
    dJointGroupEmpty(world_.contacts());
    const double delta = md_.scene.delta, plastic = kRestitutionFloor * md_.speed_scale();
    int made = 0;
    for (std::size_t j = 0; j < md_.contacts.size(); ++j) {
      const FloorContact& fc = md_.contacts[j];
      const double g = delta + u(fc.i_right) - u(fc.i_left), rate = v(fc.i_right) - v(fc.i_left);
      const bool make = active(config_.activation, g, rate, gamma_h_);
      if (make && !joint_[j] && -rate > plastic) peaks.impact(j, static_cast<double>(k + 1) * h_, -rate);
      joint_[j] = make ? 1 : 0;
      if (!make) continue;
      ++made;
      dContact c{};
      c.surface.mode = dContactBounce;
      c.surface.mu = 0.0;
      c.surface.bounce = md_.scene.eps;
      c.surface.bounce_vel = config_.bounce_vel;
      // ODE's normal points into body 1: +x, the right building's floor. On the x axis, so the
      // angular rows are exactly zero; depth 0 for a joint made ahead of time (no push-out).
      c.geom.pos[0] = u(fc.i_right);
      c.geom.normal[0] = 1.0;
      c.geom.depth = std::max(0.0, -g);
      const dJointID joint = dJointCreateContact(world_.id(), world_.contacts(), &c);
      dJointAttach(joint, bodies_[static_cast<std::size_t>(fc.i_right)], bodies_[static_cast<std::size_t>(fc.i_left)]);
      dJointSetFeedback(joint, &feedback_[j]);
    }
    return made;
  }

  // ODE's step and the state after it; false if ODE could not step.
  bool step(int rows) {
    const int stepped = config_.stepper == Stepper::quickstep ? quick_step(world_.id(), h_, rows)
                                                              : dWorldStep(world_.id(), h_);
    if (stepped == 0) return false;
    for (int i = 0; i < n_; ++i) {
      const dBodyID b = bodies_[static_cast<std::size_t>(i)];
      x_(i) = dBodyGetPosition(b)[0];
      x_(n_ + i) = dBodyGetLinearVel(b)[0];
    }
    return true;
  }

  bool dantzig_gave_up() const { return lcp_failures() != lcp_failures_before_; }

  // Every floor still on the x axis, unrotated: the model's premise.
  bool still_on_axis() const {
    for (const dBodyID b : bodies_) {
      const dReal* p = dBodyGetPosition(b);
      const dReal* vel = dBodyGetLinearVel(b);
      const dReal* w = dBodyGetAngularVel(b);
      const dReal* q = dBodyGetQuaternion(b);
      if (p[1] != 0.0 || p[2] != 0.0 || vel[1] != 0.0 || vel[2] != 0.0) return false;
      if (w[0] != 0.0 || w[1] != 0.0 || w[2] != 0.0) return false;
      if (q[0] != 1.0 || q[1] != 0.0 || q[2] != 0.0 || q[3] != 0.0) return false;
    }
    return true;
  }

 private:
  const BuildingModel& md_;
  const Config& config_;
  double h_, gamma_h_;
  int n_;
  LoadCursor load_;  // a_g at each step's start, O(1) on a record
  World world_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> smooth_;  // [K C]
  Eigen::VectorXd x_;                                    // (u, v) of every floor
  Eigen::VectorXd f_;                                    // K u + C v
  std::vector<char> joint_;                              // per contact: a joint for the last step
  std::vector<dJointFeedback> feedback_;
  std::vector<dBodyID> bodies_;  // per global floor
  long lcp_failures_before_ = 0;
};

// The n steps of h; the status and message of a run that stopped early go into r.
void run(const BuildingModel& md, const Config& config, double h, long n, const Settings& set, BuildingsResult& r,
         buildings::FloorPeaks& peaks) {
  Run ode(md, config, h, set.gamma);
  if (!ode.start()) {
    r.status = Status::failed;
    r.message = "ODE could not create a world";
    return;
  }
  peaks.sample(0.0, ode.u_data());
  Deadline deadline(set);
  long k = 0;
  const auto where = [&] { return " at step " + std::to_string(k) + " (t = " + format_number(static_cast<double>(k) * h) + ")"; };
  const auto stop = [&](Status s, const std::string& why) {
    r.status = s;
    r.message = why + where();
  };
  for (; k < n; ++k) {
    if (!ode.apply_loads(k)) {
      stop(Status::nan, "non-finite force");
      break;
    }
    const int rows = ode.make_contacts(k, peaks);
    if (!ode.step(rows)) {
      stop(Status::failed, "ODE could not step (working memory)");
      break;
    }
    if (ode.dantzig_gave_up()) {
      ++k;
      stop(Status::failed, "ODE's Dantzig LCP gave up (a tie it cannot pivot through)");
      break;
    }
    if (!buildings::end_step(md, k, n, h, ode.u_data(), ode.u_data() + md.n_floors, peaks, &deadline, r)) {
      ++k;
      break;
    }
  }
  r.events = k;
  if (r.status == Status::ok && !ode.still_on_axis()) {
    r.status = Status::failed;
    r.message = "a floor left the x axis or rotated";
  }
  if (std::string notes = take_messages(); !notes.empty()) r.message += (r.message.empty() ? "" : "; ") + notes;
}

}  // namespace

}  // namespace floors

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings) {
  if (std::string why = validate(model.scene); !why.empty()) return buildings::failed(why);
  if (std::string why = check(settings); !why.empty()) return buildings::failed(why);
  const std::optional<Config> config = kVariants.find(settings.variant);
  if (!config) return buildings::failed("unknown variant " + settings.variant);
  buildings::BuildingsResult r;
  long n = 0;
  if (!buildings::plan_steps(model, settings, kDefaultSteps, r, n)) return r;
  if (!prepare_thread()) return buildings::failed("ODE could not be initialised on this thread", r.step);
  buildings::FloorPeaks peaks(model);
  try {
    floors::run(model, *config, r.step, n, settings, r, peaks);
  } catch (const std::exception& e) {
    r.status = Status::failed;
    r.message = std::string("ODE: ") + e.what();
  }
  peaks.into(r);
  return r;
}

}  // namespace pb::ode
