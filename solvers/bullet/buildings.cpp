#include "solvers/bullet/buildings.hpp"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btEmptyShape.h>
#include <BulletDynamics/MLCPSolvers/btDantzigSolver.h>
#include <BulletDynamics/MLCPSolvers/btLemkeSolver.h>
#include <BulletDynamics/MLCPSolvers/btMLCPSolver.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "cases/text.hpp"
#include "kit/buildings_step_end.hpp"
#include "kit/fixed_step.hpp"
#include "kit/run_limits.hpp"
#include "solvers/bullet/bullet_solver.hpp"
#include "solvers/bullet/engine.hpp"

namespace pb::bullet {

// Named, not anonymous: a unity build puts this file beside the single oscillators' World.
namespace floors {

namespace {

using buildings::BuildingsResult;

// The Bullet objects of one run and its step (engine.hpp's World, with a body per floor and
// the buildings' K and C).
class Floors {
 public:
  Floors(const BuildingModel& md, const Config& config, double h, double gamma)
      : md_(md),
        n_(md.n_floors),
        h_(h),
        gamma_h_(gamma * h),
        plastic_(kRestitutionFloor * md.speed_scale()),
        info_(solver_info(config, h)),
        activation_(config.activation),
        load_(md.scene.pulse) {
    Eigen::MatrixXd both(n_, 2 * n_);
    both << md.K, md.C;
    smooth_ = both.sparseView();
    x_.setZero(2 * n_);
    f_.setZero(n_);
    shape_ = std::make_unique<btEmptyShape>();
    for (int i = 0; i < n_; ++i) {
      bodies_.push_back(make_body(shape_.get(), md.m(i), 0.0, 0.0, md.scene.eps));
      body_list_.push_back(bodies_.back().get());
    }
    for (const FloorContact& fc : md.contacts) {
      const btCollisionObject* a = bodies_[static_cast<std::size_t>(fc.i_right)].get();
      const btCollisionObject* b = bodies_[static_cast<std::size_t>(fc.i_left)].get();
      manifolds_.push_back(std::make_unique<btPersistentManifold>(a, b, 0, gContactBreakingThreshold, BT_LARGE_FLOAT));
      // faithful: eps itself; default: Bullet's combination of the floors' restitutions (eps^2).
      restitution_.push_back(config.faithful ? static_cast<btScalar>(md.scene.eps)
                                             : btManifoldResult::calculateCombinedRestitution(a, b));
    }
    // Friction cannot act (the tangential axes are locked); faithful bounds it by 1 all the
    // same, for btLemkeSolver (engine.cpp, README "Variants").
    friction_ = config.faithful ? 1 : 0;
    touching_.assign(md.contacts.size(), nullptr);
    switch (config.engine) {
      case Engine::si: solver_ = std::make_unique<btSequentialImpulseConstraintSolver>(); break;
      case Engine::mlcp_dantzig:
        mlcp_ = std::make_unique<btDantzigSolver>();
        serial_ = &dantzig_solves();
        break;
      case Engine::mlcp_lemke: mlcp_ = std::make_unique<btLemkeSolver>(); break;
    }
    if (mlcp_) solver_ = std::make_unique<btMLCPSolver>(mlcp_.get());
  }
  ~Floors() {
    for (auto& m : manifolds_) m->clearManifold();
  }
  Floors(const Floors&) = delete;
  Floors& operator=(const Floors&) = delete;

  double u(int i) const { return x_(i); }
  double v(int i) const { return x_(n_ + i); }
  const double* u_data() const { return x_.data(); }

  // Step k, from t_k = k h; the impacts of its new points go to peaks at the step's end.
  // False if a force is not finite (Bullet never sees one).
  bool step(long k, buildings::FloorPeaks& peaks) {
    int touching = 0;
    for (std::size_t j = 0; j < manifolds_.size(); ++j) {
      btPersistentManifold& m = *manifolds_[j];
      const FloorContact& fc = md_.contacts[j];
      const double g = md_.scene.delta + u(fc.i_right) - u(fc.i_left), rate = v(fc.i_right) - v(fc.i_left);
      if (active(activation_, g, rate, gamma_h_)) {
        btManifoldPoint p(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(1, 0, 0),
                          static_cast<btScalar>(std::min(g, 0.0)));
        p.m_positionWorldOnA = m.getBody0()->getWorldTransform().getOrigin();
        p.m_positionWorldOnB = m.getBody1()->getWorldTransform().getOrigin();
        p.m_combinedRestitution = restitution_[j];
        p.m_combinedFriction = friction_;
        if (m.getNumContacts() == 0) {
          m.addManifoldPoint(p);
          if (-rate > plastic_) peaks.impact(j, static_cast<double>(k + 1) * h_, -rate);
        } else {
          m.replaceContactPoint(p, 0);
        }
        touching_[static_cast<std::size_t>(touching++)] = &m;
      } else if (m.getNumContacts() > 0) {
        m.clearManifold();
      }
    }
    const double a_g = load_.accel(static_cast<double>(k) * h_);
    f_.noalias() = smooth_ * x_;
    for (int i = 0; i < n_; ++i) {
      const double f = -f_(i) - md_.m(i) * a_g;
      if (!std::isfinite(f)) return false;
      bodies_[static_cast<std::size_t>(i)]->applyCentralForce(btVector3(static_cast<btScalar>(f), 0, 0));
    }
    {
      std::unique_lock<std::mutex> one_at_a_time;
      if (serial_) one_at_a_time = std::unique_lock(*serial_);
      solver_->solveGroup(body_list_.data(), static_cast<int>(body_list_.size()), touching_.data(), touching, nullptr,
                          0, info_, nullptr, nullptr);
    }
    for (int i = 0; i < n_; ++i) {
      btRigidBody& body = *bodies_[static_cast<std::size_t>(i)];
      btTransform next;
      body.predictIntegratedTransform(info_.m_timeStep, next);
      body.proceedToTransform(next);
      body.clearForces();
      x_(i) = body.getWorldTransform().getOrigin().x();
      x_(n_ + i) = body.getLinearVelocity().x();
    }
    return true;
  }

  // Steps in which the MLCP solver failed and Bullet fell back to sequential impulse.
  int fallbacks() const { return mlcp_ ? static_cast<btMLCPSolver*>(solver_.get())->getNumFallbacks() : 0; }

 private:
  const BuildingModel& md_;
  int n_;
  double h_, gamma_h_, plastic_;
  btContactSolverInfo info_;
  Activation activation_;
  LoadCursor load_;  // a_g at each step's start, O(1) on a record
  Eigen::SparseMatrix<double, Eigen::RowMajor> smooth_;  // [K C]
  Eigen::VectorXd x_;                                    // (u, v) of every floor, read from Bullet
  Eigen::VectorXd f_;                                    // K u + C v
  std::unique_ptr<btCollisionShape> shape_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;  // per global floor
  std::vector<btCollisionObject*> body_list_;
  std::vector<std::unique_ptr<btPersistentManifold>> manifolds_;  // per contact
  std::vector<btPersistentManifold*> touching_;
  std::vector<btScalar> restitution_;
  btScalar friction_ = 0;
  std::unique_ptr<btMLCPSolverInterface> mlcp_;  // declared before solver_, which uses it
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::mutex* serial_ = nullptr;
};

// The n steps of h; the status and message of a run that stopped early go into r.
void run(const BuildingModel& md, const Config& config, double h, long n, const Settings& set, BuildingsResult& r,
         buildings::FloorPeaks& peaks) {
  Floors world(md, config, h, set.gamma);
  peaks.sample(0.0, world.u_data());
  Deadline deadline(set);
  long k = 0;
  const auto stop = [&](Status s, const std::string& why) {
    r.status = s;
    r.message = why + " at step " + std::to_string(k) + " (t = " + format_number(static_cast<double>(k) * h) + ")";
  };
  for (; k < n; ++k) {
    if (!world.step(k, peaks)) {
      stop(Status::nan, "non-finite force");
      break;
    }
    if (!buildings::end_step(md, k, n, h, world.u_data(), world.u_data() + md.n_floors, peaks, &deadline, r)) {
      ++k;
      break;
    }
  }
  r.events = k;
  if (const int fb = world.fallbacks(); fb > 0)
    r.message += (r.message.empty() ? "" : "; ") + std::string("the MLCP solver failed in ") + std::to_string(fb) +
                 " steps (Bullet fell back to sequential impulse)";
}

}  // namespace

}  // namespace floors

buildings::BuildingsResult solve_buildings(const BuildingModel& model, const Settings& settings) {
  if (std::string why = validate(model.scene); !why.empty()) return buildings::failed(why);
  if (std::string why = check(settings); !why.empty()) return buildings::failed(why);
  const std::optional<Config> config = kVariants.find(settings.variant);
  if (!config) return buildings::failed("unknown variant '" + settings.variant + "'");
  buildings::BuildingsResult r;
  long n = 0;
  if (!buildings::plan_steps(model, settings, kDefaultSteps, r, n)) return r;
  buildings::FloorPeaks peaks(model);
  try {
    floors::run(model, *config, r.step, n, settings, r, peaks);
  } catch (const std::exception& e) {
    r.status = Status::failed;
    r.message = std::string("Bullet: ") + e.what();
  }
  peaks.into(r);
  return r;
}

}  // namespace pb::bullet
