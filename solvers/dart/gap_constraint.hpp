#pragma once
// The faithful variants' contact: one gap of the scene as a DART constraint of its own, a
// ConstraintBase added to the world's ConstraintSolver (no shapes, no collision detection).
//
// DART's own ContactConstraint cannot be made faithful (solvers/dart/README.md): its bounce
// is skipped below DART_BOUNCING_VELOCITY_THRESHOLD (0.1 in user units, compiled in), its
// restitution is the product of two shapes' coefficients and targets the velocity after the
// step's forces, and its push-out and softening are process-wide statics. This one row is
// ODE's faithful contact row, in DART's LCP form A x = b + w (x the impulse, w >= 0,
// complementary):
//
//   b = target - g'_free,   target = eps max(0, -g'_k)
//
// g'_free the gap rate after the step's forces (what the bodies move at when the solver
// builds the row), g'_k the rate at the step's start, which the engine hands in with the
// decision whether the row takes part in the step (the activation rule of
// kit/fixed_step.hpp). Each body sits on a prismatic joint along x, the only body of its
// own skeleton, so the Jacobian is +1 on the right body's x and -1 on the left's (none for the
// wall), and a unit impulse moves its two skeletons alone. Like DART's ContactConstraint, the
// constraint unites its two skeletons for the constraint solver, which then solves the
// contacts of bodies that touch through others as one LCP (a constrained group), and apart
// from those that do not.
//
// Rejected: one skeleton for every building, a tree each (this project's first model). DART
// resizes a skeleton's n x n caches for every body added to it, O(n^3) in all: 35-40 s of CPU
// for 1000 bodies, against 0.3 s now (wall, loaded machine); and each unit impulse then
// updated every body of the skeleton, O(n) per contact row of the LCP's matrix.

#include <dart/constraint/ConstraintBase.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/Skeleton.hpp>

#include "solvers/dart/run_limit.hpp"

namespace pb::dart {

class GapConstraint : public ::dart::constraint::ConstraintBase {
 public:
  // left is null for the wall. Each body is its own skeleton's only one. The run's limit is
  // ticked at each unit impulse (run_limit.hpp).
  GapConstraint(::dart::dynamics::BodyNode* left, ::dart::dynamics::BodyNode* right, RunLimit& limit);

  // For the coming step: whether the row takes part, and the target separation speed.
  void arm(bool active, double target) {
    active_ = active;
    target_ = target;
    impulse_ = 0.0;
  }
  // The impulse the solver applied in the last step (0 when the row took no part).
  double impulse() const { return impulse_; }

  void update() override {}
  void getInformation(::dart::constraint::ConstraintInfo* info) override;
  void applyUnitImpulse(std::size_t index) override;
  void getVelocityChange(double* vel, bool withCfm) override;
  void excite() override;
  void unexcite() override;
  void applyImpulse(double* lambda) override;
  bool isActive() const override { return active_; }
  ::dart::dynamics::SkeletonPtr getRootSkeleton() const override;
  void uniteSkeletons() override;

 private:
  double rate() const;  // g' of the bodies' current velocities

  ::dart::dynamics::BodyNode* left_;
  ::dart::dynamics::BodyNode* right_;
  RunLimit& limit_;
  bool active_ = false;
  double target_ = 0.0;
  double impulse_ = 0.0;
};

}  // namespace pb::dart
