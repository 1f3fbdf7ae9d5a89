#include "solvers/bullet/engine.hpp"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btEmptyShape.h>
#include <BulletDynamics/MLCPSolvers/btDantzigSolver.h>
#include <BulletDynamics/MLCPSolvers/btLemkeSolver.h>
#include <BulletDynamics/MLCPSolvers/btMLCPSolver.h>

#include <algorithm>

namespace pb::bullet {

// Bullet's Dantzig LCP (btDantzigLCP.cpp) keeps its failure flag in a global, s_error, which
// every solve clears and sets as it pivots: two worlds solving at once on two threads read
// each other's failures, and a step falls back to Bullet's projected Gauss-Seidel
// (btMLCPSolver) or not by their timing. Measured: 13 of the stress set's 1232 points on
// mlcp-dantzig-faithful at w_max h = 2 changed status between two runs of the same 2-thread
// sweep, none with one thread. So its solves are taken one at a time, process-wide.
std::mutex& dantzig_solves() {
  static std::mutex lock;
  return lock;
}

btContactSolverInfo solver_info(const Config& config, double h) {
  btContactSolverInfo info;  // Bullet's defaults (btContactSolverInfo.h)
  info.m_timeStep = static_cast<btScalar>(h);
  if (!config.faithful) return info;
  // Each value and why: solvers/bullet/README.md, "faithful".
  info.m_numIterations = kFaithfulIterations;
  info.m_erp2 = 0;                          // no Baumgarte push-out of contacts
  info.m_erp = 0;                           // (joints; there are none)
  info.m_splitImpulse = 0;                  // no positional correction either
  info.m_restitutionVelocityThreshold = 0;  // restitution at every approach speed
  // Warm starting off, but the flag stays: solveGroup writes the applied impulse back to
  // the manifold point only with SOLVER_USE_WARMSTARTING set, and a factor of zero makes
  // the warm start itself nothing (0 * last impulse, applied as a zero impulse).
  info.m_warmstartingFactor = 0;
  info.m_solverMode |= SOLVER_USE_WARMSTARTING;
  return info;
}

std::unique_ptr<btRigidBody> make_body(btCollisionShape* shape, double mass, double u0, double v0, double restitution) {
  btRigidBody::btRigidBodyConstructionInfo ci(static_cast<btScalar>(mass), nullptr, shape, btVector3(0, 0, 0));
  ci.m_startWorldTransform.setIdentity();
  ci.m_startWorldTransform.setOrigin(btVector3(static_cast<btScalar>(u0), 0, 0));
  ci.m_linearDamping = 0;
  ci.m_angularDamping = 0;
  ci.m_friction = 0;
  ci.m_rollingFriction = 0;
  ci.m_spinningFriction = 0;
  ci.m_restitution = static_cast<btScalar>(restitution);
  auto body = std::make_unique<btRigidBody>(ci);
  if (mass > 0.0) {
    body->setLinearFactor(btVector3(1, 0, 0));
    body->setAngularFactor(0);
    body->setGravity(btVector3(0, 0, 0));
    body->setDamping(0, 0);
    body->setActivationState(DISABLE_DEACTIVATION);
    // Bullet's default implicit gyroscopic term is exactly zero for a body that cannot
    // rotate, and computing it was a quarter of the cost of a step.
    body->setFlags(body->getFlags() & ~(BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT | BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD |
                                        BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY));
    body->setLinearVelocity(btVector3(static_cast<btScalar>(v0), 0, 0));
  }
  return body;
}

World::World(const System& system, const Config& config, double h, double gamma, const std::vector<double>& u0,
             const std::vector<double>& v0)
    : system_(system),
      load_(system.pulse),
      info_(solver_info(config, h)),
      activation_(config.activation),
      gamma_h_(gamma * h),
      u_(u0.size()),
      v_(v0.size()),
      springs_(system, u0) {
  const int nb = system.n_bodies(), nc = system.n_contacts();
  shape_ = std::make_unique<btEmptyShape>();  // no geometry: contacts come from the gaps
  for (int i = 0; i < nb; ++i) {
    const Body& b = system.bodies[ix(i)];
    c_.push_back(b.c);
    m_.push_back(b.m);
    bodies_.push_back(make_body(shape_.get(), b.m, u0[ix(i)], v0[ix(i)], system.eps));
    body_list_.push_back(bodies_.back().get());
  }
  // The wall is a static body (mass 0) at the origin: the ground frame.
  if (system.wall) wall_ = make_body(shape_.get(), 0.0, 0.0, 0.0, system.eps);
  for (int j = 0; j < nc; ++j) {
    const int left = system.left(j);
    const btCollisionObject* a = bodies_[ix(system.right(j))].get();
    const btCollisionObject* b = left == kWall ? wall_.get() : bodies_[ix(left)].get();
    // Thresholds: a point's distance is never positive (step 1 in engine.hpp), so Bullet's
    // breaking threshold never removes one and the processing threshold (Bullet's default,
    // BT_LARGE_FLOAT) lets every point into the solver.
    manifolds_.push_back(std::make_unique<btPersistentManifold>(a, b, 0, gContactBreakingThreshold, BT_LARGE_FLOAT));
    // faithful: the combined restitution is eps itself; default: Bullet's combination of
    // the two bodies' restitutions (the product, eps^2, unless eps is 0 or 1).
    restitution_.push_back(config.faithful ? static_cast<btScalar>(system.eps)
                                           : btManifoldResult::calculateCombinedRestitution(a, b));
  }
  // Friction cannot act here: the tangential axes are locked (linear factor) and every
  // tangential velocity is exactly zero, so a friction row's impulse is zero whatever its
  // bound. faithful gives it a bound of 1 all the same, because btLemkeSolver turns a
  // friction row with bounds [0, 0] into a degenerate LCP and then returns A^-1 b, which
  // pulls on separating contacts (README); default keeps Bullet's product of the bodies'
  // frictions, 0.
  friction_ = config.faithful ? 1 : 0;
  touching_.assign(ix(nc), nullptr);
  added_.assign(ix(nc), 0);
  switch (config.engine) {
    case Engine::si: solver_ = std::make_unique<btSequentialImpulseConstraintSolver>(); break;
    case Engine::mlcp_dantzig:
      mlcp_ = std::make_unique<btDantzigSolver>();
      serial_ = &dantzig_solves();
      break;
    case Engine::mlcp_lemke: mlcp_ = std::make_unique<btLemkeSolver>(); break;
  }
  if (mlcp_) {
    solver_ = std::make_unique<btMLCPSolver>(mlcp_.get());
    is_mlcp_ = true;
  }
}

World::~World() {
  for (auto& m : manifolds_) m->clearManifold();
}

double World::impulse(int j) const {
  const btPersistentManifold& m = *manifolds_[ix(j)];
  return m.getNumContacts() > 0 ? m.getContactPoint(0).m_appliedImpulse : 0.0;
}

int World::fallbacks() const { return is_mlcp_ ? static_cast<btMLCPSolver*>(solver_.get())->getNumFallbacks() : 0; }

void World::step(double t) {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    u_[i] = u(static_cast<int>(i));
    v_[i] = v(static_cast<int>(i));
  }
  int touching = 0;
  for (std::size_t j = 0; j < manifolds_.size(); ++j) {
    btPersistentManifold& m = *manifolds_[j];
    const int jj = static_cast<int>(j);
    const double g = system_.gap(jj, u_.data());
    added_[j] = 0;
    if (active(activation_, g, system_.gap_rate(jj, v_.data()), gamma_h_)) {
      const auto distance = static_cast<btScalar>(std::min(g, 0.0));
      btManifoldPoint p(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(1, 0, 0), distance);
      // The point is each body's own origin, so rel_pos is exactly zero (no lever arm).
      p.m_positionWorldOnA = m.getBody0()->getWorldTransform().getOrigin();
      p.m_positionWorldOnB = m.getBody1()->getWorldTransform().getOrigin();
      p.m_combinedRestitution = restitution_[j];
      p.m_combinedFriction = friction_;
      if (m.getNumContacts() == 0) {
        m.addManifoldPoint(p);
        added_[j] = 1;
      } else {
        m.replaceContactPoint(p, 0);
      }
      touching_[static_cast<std::size_t>(touching++)] = &m;
    } else if (m.getNumContacts() > 0) {
      m.clearManifold();
    }
  }

  const double ag = load_.accel(t);
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    btRigidBody& b = *bodies_[i];
    const double u_i = b.getWorldTransform().getOrigin().x(), v_i = b.getLinearVelocity().x();
    const double f = -springs_.force(static_cast<int>(i), u_i, ag) - c_[i] * v_i - m_[i] * ag;
    b.applyCentralForce(btVector3(static_cast<btScalar>(f), 0, 0));
  }

  {
    std::unique_lock<std::mutex> one_at_a_time;
    if (serial_) one_at_a_time = std::unique_lock(*serial_);
    solver_->solveGroup(body_list_.data(), static_cast<int>(body_list_.size()), touching_.data(), touching, nullptr,
                        0, info_, nullptr, nullptr);
  }

  for (auto& body : bodies_) {
    btTransform next;
    body->predictIntegratedTransform(info_.m_timeStep, next);
    body->proceedToTransform(next);
    body->clearForces();
  }
}

void World::finish_springs(Result& res) {
  std::vector<double> u(bodies_.size());
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = this->u(static_cast<int>(i));
  springs_.finish(u.data(), res);
}

}  // namespace pb::bullet
