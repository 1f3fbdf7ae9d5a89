#include "solvers/dart/gap_constraint.hpp"

#include <limits>

#include <dart/dynamics/Joint.hpp>

namespace pb::dart {

namespace {

// A unit impulse along +x on a body, in its own frame (angular part first). The bodies
// never rotate, so their frames stay parallel to the world's.
Eigen::Vector6d along_x(double sign) {
  Eigen::Vector6d imp = Eigen::Vector6d::Zero();
  imp[3] = sign;
  return imp;
}

// The velocity change of a unit impulse along `sign` x on the body, its skeleton's only one.
void unit_impulse(::dart::dynamics::BodyNode* body, double sign) {
  ::dart::dynamics::Skeleton* skel = body->getSkeleton().get();
  skel->clearConstraintImpulses();
  skel->updateBiasImpulse(body, along_x(sign));
  skel->updateVelocityChange();
}

// The body's x velocity change in the unit impulse under test: none unless its skeleton is
// the tested constraint's (excited).
double velocity_change(const ::dart::dynamics::BodyNode* body) {
  return body->getSkeleton()->isImpulseApplied() ? body->getBodyVelocityChange()[3] : 0.0;
}

}  // namespace

GapConstraint::GapConstraint(::dart::dynamics::BodyNode* left, ::dart::dynamics::BodyNode* right, RunLimit& limit)
    : left_(left), right_(right), limit_(limit) {
  mDim = 1;
}

double GapConstraint::rate() const {
  const double v_right = right_->getParentJoint()->getVelocity(0);
  return left_ ? v_right - left_->getParentJoint()->getVelocity(0) : v_right;
}

void GapConstraint::getInformation(::dart::constraint::ConstraintInfo* info) {
  info->x[0] = 0.0;
  info->w[0] = 0.0;
  info->lo[0] = 0.0;
  info->hi[0] = std::numeric_limits<double>::infinity();
  info->findex[0] = -1;
  info->b[0] = target_ - rate();
}

void GapConstraint::applyUnitImpulse(std::size_t) {
  limit_.tick();  // may throw OutOfTime: DART is filling its LCP's matrix
  unit_impulse(right_, 1.0);
  if (left_) unit_impulse(left_, -1.0);
}

void GapConstraint::getVelocityChange(double* vel, bool) {
  // No softening (DART's ContactConstraint scales the diagonal by 1 + CFM here).
  vel[0] = velocity_change(right_) - (left_ ? velocity_change(left_) : 0.0);
}

void GapConstraint::excite() {
  right_->getSkeleton()->setImpulseApplied(true);
  if (left_) left_->getSkeleton()->setImpulseApplied(true);
}

void GapConstraint::unexcite() {
  right_->getSkeleton()->setImpulseApplied(false);
  if (left_) left_->getSkeleton()->setImpulseApplied(false);
}

void GapConstraint::applyImpulse(double* lambda) {
  impulse_ = lambda[0];
  right_->addConstraintImpulse(along_x(lambda[0]));
  if (left_) left_->addConstraintImpulse(along_x(-lambda[0]));
}

::dart::dynamics::SkeletonPtr GapConstraint::getRootSkeleton() const {
  return ConstraintBase::getRootSkeleton(right_->getSkeleton());
}

// Union by size, as DART's ContactConstraint unites its two bodies' skeletons.
void GapConstraint::uniteSkeletons() {
  if (!left_) return;
  const ::dart::dynamics::SkeletonPtr a = compressPath(left_->getSkeleton());
  const ::dart::dynamics::SkeletonPtr b = compressPath(right_->getSkeleton());
  if (a == b) return;
  if (a->mUnionSize < b->mUnionSize) {
    a->mUnionRootSkeleton = b;
    b->mUnionSize += a->mUnionSize;
  } else {
    b->mUnionRootSkeleton = a;
    a->mUnionSize += b->mUnionSize;
  }
}

}  // namespace pb::dart
