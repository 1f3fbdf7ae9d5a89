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

}  // namespace

GapConstraint::GapConstraint(::dart::dynamics::BodyNode* left, ::dart::dynamics::BodyNode* right)
    : left_(left), right_(right) {
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
  ::dart::dynamics::Skeleton* skel = right_->getSkeleton().get();
  skel->clearConstraintImpulses();
  if (left_)
    skel->updateBiasImpulse(right_, along_x(1.0), left_, along_x(-1.0));
  else
    skel->updateBiasImpulse(right_, along_x(1.0));
  skel->updateVelocityChange();
}

void GapConstraint::getVelocityChange(double* vel, bool) {
  // No softening (DART's ContactConstraint scales the diagonal by 1 + CFM here).
  vel[0] = 0.0;
  if (!right_->getSkeleton()->isImpulseApplied()) return;
  vel[0] = right_->getBodyVelocityChange()[3] - (left_ ? left_->getBodyVelocityChange()[3] : 0.0);
}

void GapConstraint::excite() { right_->getSkeleton()->setImpulseApplied(true); }

void GapConstraint::unexcite() { right_->getSkeleton()->setImpulseApplied(false); }

void GapConstraint::applyImpulse(double* lambda) {
  impulse_ = lambda[0];
  right_->addConstraintImpulse(along_x(lambda[0]));
  if (left_) left_->addConstraintImpulse(along_x(-lambda[0]));
}

::dart::dynamics::SkeletonPtr GapConstraint::getRootSkeleton() const {
  return ConstraintBase::getRootSkeleton(right_->getSkeleton());
}

}  // namespace pb::dart
