#pragma once
// The Bullet objects of one run and the step that drives them.
//
// A step is btDiscreteDynamicsWorld::internalSingleStepSimulation with the collision
// detection replaced by the scene's known gaps:
//   1. contacts   for each contact j that the variant's activation rule takes at the start
//                 of the step (kit/fixed_step.hpp), its
//                 btPersistentManifold holds one btManifoldPoint: normal +x on the left
//                 body (B) towards the right one (A), distance min(g_j, 0), restitution and
//                 friction as the variant sets them (friction never acts: see below). A point that persists from the last
//                 step is refreshed with replaceContactPoint (which keeps its applied
//                 impulse for warm starting, as Bullet's narrowphase does); a contact
//                 that the rule no longer takes is cleared. The distance of a point made
//                 ahead of time (g_j > 0) is 0: Bullet reads a positive distance as a
//                 speculative contact and lowers the row's target by distance / h, which
//                 would mix a position-level look-ahead into Newton's law (README).
//   2. forces     -k u - c v - m a_g(t_k) from the state at the start of the step
//                 (applyCentralForce).
//   3. solve      solveGroup(bodies, manifolds with a point) of the variant's solver: it
//                 sets up Bullet's contact constraints (restitution, ERP, split impulse,
//                 warm start), solves them and writes back v + h F/m + impulse/m.
//   4. positions  predictIntegratedTransform + proceedToTransform (x += h v_new), then
//                 clearForces: Bullet's integrateTransforms.
//
// Bodies sit at x = u (ground-relative displacement), all at the origin at rest, and the
// gap delta lives only in the distance of the manifold point: Bullet's float positions
// then carry u itself, with ~6e-8 |u| resolution, instead of u plus a spacing (see
// solvers/bullet/README.md, single precision).
//
// Nothing here is shared between runs: each World owns its shape, bodies, manifolds and
// solver, so worlds may step in parallel threads (README: thread safety).

#include <btBulletDynamicsCommon.h>

#include <BulletDynamics/MLCPSolvers/btMLCPSolverInterface.h>

#include <memory>
#include <mutex>
#include <vector>

#include "cases/system.hpp"
#include "solvers/bullet/variants.hpp"
#include "kit/hysteresis.hpp"

namespace pb::bullet {

// The btContactSolverInfo of a variant at step h: Bullet's defaults, then the faithful
// overrides. The only place where a setting of a variant is chosen.
btContactSolverInfo solver_info(const Config& config, double h);

// A body on the x axis alone (linear factor (1,0,0), no rotation, gravity, damping or
// sleep), frictionless, of restitution `restitution`, at x = u0 moving at v0; mass 0: static.
// The single oscillators' bodies and the buildings' floors (buildings.cpp).
std::unique_ptr<btRigidBody> make_body(btCollisionShape* shape, double mass, double u0, double v0, double restitution);

// Bullet's Dantzig LCP keeps its failure flag in a global: its solves are taken one at a
// time, process-wide, under this lock (engine.cpp says what it measured without it).
std::mutex& dantzig_solves();

class World {
 public:
  // u0, v0: one value per body, left to right.
  World(const System& system, const Config& config, double h, double gamma, const std::vector<double>& u0,
        const std::vector<double>& v0);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // One step from t = t_k to t_k + h.
  void step(double t);

  double u(int i) const { return bodies_[ix(i)]->getWorldTransform().getOrigin().x(); }
  double v(int i) const { return bodies_[ix(i)]->getLinearVelocity().x(); }
  // Whether contact j had a manifold point in the last step, and whether it was new then.
  bool in_contact(int j) const { return manifolds_[ix(j)]->getNumContacts() > 0; }
  bool added(int j) const { return added_[ix(j)] != 0; }
  // The normal impulse Bullet applied at contact j in the last step (0 without a point).
  double impulse(int j) const;
  // Steps in which the MLCP solver failed and Bullet fell back to sequential impulse.
  int fallbacks() const;
  // The yielding responses (residual, hysteretic share) from the current state.
  void finish_springs(Result& res);

 private:
  const System& system_;
  LoadCursor load_;  // a_g(t) of each step, O(1) on a record
  btContactSolverInfo info_;
  Activation activation_;
  double gamma_h_;                 // Settings::gamma h, for the predicted rule
  std::vector<double> u_, v_;      // the state at the start of a step, per body
  std::vector<double> c_, m_;      // per body
  StepSprings springs_;            // the bodies' springs (hysteresis.hpp)
  std::unique_ptr<btCollisionShape> shape_;
  std::unique_ptr<btRigidBody> wall_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<btCollisionObject*> body_list_;  // what solveGroup takes
  std::vector<std::unique_ptr<btPersistentManifold>> manifolds_;
  std::vector<btPersistentManifold*> touching_;  // manifolds with a point this step
  std::vector<btScalar> restitution_;             // combined restitution per contact
  btScalar friction_ = 0;                         // combined friction of every point
  std::vector<char> added_;
  std::unique_ptr<btMLCPSolverInterface> mlcp_;  // declared before solver_, which uses it
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  bool is_mlcp_ = false;
  std::mutex* serial_ = nullptr;  // held around each solve where Bullet's solver is not thread-safe
};

}  // namespace pb::bullet
