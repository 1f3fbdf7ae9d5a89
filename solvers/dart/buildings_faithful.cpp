// The faithful variants on the buildings scene (buildings.hpp): the single oscillators'
// faithful model (faithful.cpp) with one body per floor.
//
//   bodies    a skeleton per floor: a BodyNode of mass m_i on a PrismaticJoint along x from the
//             world (the joint coordinate is u_i), no shapes, no gravity, no joint spring or
//             damper. A skeleton per floor, not a chain per building: the floors then move
//             only through the forces below and the contacts (whose unit impulses move two
//             one-body skeletons), and DART's skeleton caches stay 1 x 1 (gap_constraint.hpp).
//   forces    -(K u)_i - (C v)_i - m_i a_g(t_k) at the step's start as the joint's force: the
//             storeys' springs and the building's whole C (Rayleigh or modal: DART has no
//             spring or damper between two bodies of different skeletons, and a modal C couples
//             every floor of a building), so the scheme is ODE's faithful step, semi-implicit
//             Euler with explicit springs.
//   contacts  a GapConstraint per floor contact, armed each step by the activation rule from
//             the state at the step's start, with the target eps max(0, -g'_k).
//   lcp       BoxedLcpConstraintSolver with Dantzig's solver or PGS, no fallback; a Dantzig
//             failure ends the run failed, naming the step.

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/SparseCore>
#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/PrismaticJoint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/simulation/World.hpp>

#include "kit/fixed_step.hpp"
#include "solvers/dart/buildings_models.hpp"
#include "solvers/dart/gap_constraint.hpp"
#include "solvers/dart/lcp.hpp"

namespace pb::dart {

// Named, not anonymous: a unity build puts this file beside faithful.cpp.
namespace floors_faithful {

namespace {

class Faithful : public FloorsEngine {
 public:
  Faithful(const BuildingModel& md, const Config& config, const Settings& set, double h, RunLimit& limit)
      : FloorsEngine(md), md_(md), config_(config), gamma_h_(set.gamma * h),
        was_active_(md.contacts.size(), 0), limit_(limit) {
    const int n = md.n_floors;
    // -[K, C] by rows, for the joints' forces from x = (u, v): one sparse product a step.
    Eigen::MatrixXd both(n, 2 * n);
    both << -md.K, -md.C;
    smooth_ = both.sparseView();
    x_.setZero(2 * n);
    f_.setZero(n);
    prepare_process();
    world_ = ::dart::simulation::World::create("buildings");
    world_->setGravity(Eigen::Vector3d::Zero());
    world_->setTimeStep(h);
    lcp_ = set_faithful_solver(*world_, config.lcp == Lcp::pgs, kFaithfulPgsSweeps, limit);
    for (int i = 0; i < n; ++i) add_floor(i);
    for (const FloorContact& fc : md.contacts) {
      auto gap = std::make_shared<GapConstraint>(bodies_[static_cast<std::size_t>(fc.i_left)],
                                                 bodies_[static_cast<std::size_t>(fc.i_right)], limit);
      world_->getConstraintSolver()->addConstraint(gap);
      gaps_.push_back(std::move(gap));
    }
    messages_before_ = lcp_messages();
  }

  bool step(long k, double a_g, buildings::BuildingsResult& r) override {
    const int n = md_.n_floors;
    for (int i = 0; i < n; ++i) {
      x_(i) = u_[static_cast<std::size_t>(i)];
      x_(n + i) = v_[static_cast<std::size_t>(i)];
    }
    f_.noalias() = smooth_ * x_;
    for (int i = 0; i < n; ++i) {
      const double f = f_(i) - md_.m(i) * a_g;
      if (!std::isfinite(f)) {
        r.status = Status::nan;
        r.message = "non-finite force at step " + std::to_string(k + 1);
        return false;
      }
      joints_[static_cast<std::size_t>(i)]->setForce(0, f);
    }
    for (std::size_t j = 0; j < gaps_.size(); ++j) {
      const FloorContact& fc = md_.contacts[j];
      const auto l = static_cast<std::size_t>(fc.i_left), rt = static_cast<std::size_t>(fc.i_right);
      const double g = md_.scene.delta + u_[rt] - u_[l], rate = v_[rt] - v_[l];
      const bool on = active(config_.activation, g, rate, gamma_h_);
      gaps_[j]->arm(on, rate < 0.0 ? -md_.scene.eps * rate : 0.0);
      entered_[j] = on && !was_active_[j] ? 1 : 0;
      was_active_[j] = on ? 1 : 0;
    }
    const long failures_before = lcp_.dantzig ? lcp_.dantzig->failures : 0;
    limit_.tick();
    world_->step();
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      u_[i] = joints_[i]->getPosition(0);
      v_[i] = joints_[i]->getVelocity(0);
    }
    if (lcp_.dantzig && lcp_.dantzig->failures != failures_before) {
      r.status = Status::failed;
      r.message = "DART's Dantzig LCP gave up (degenerate pivot) at step " + std::to_string(k + 1) +
                  ": the contact impulses of that step are wrong";
      return false;
    }
    return true;
  }

  void finish(buildings::BuildingsResult& r) override {
    if (lcp_.pgs && lcp_.pgs->failures > 0)
      add_note(r, "PGS stopped at its " + std::to_string(kFaithfulPgsSweeps) + " sweeps unconverged in " +
                      std::to_string(lcp_.pgs->failures) + " steps");
    if (const long m = lcp_messages() - messages_before_; m > 0)
      add_note(r, "DART's LCP warned " + std::to_string(m) + " times");
  }

 private:
  void add_floor(int i) {
    limit_.tick();
    auto skel = ::dart::dynamics::Skeleton::create("floor" + std::to_string(i));
    ::dart::dynamics::PrismaticJoint::Properties joint;
    joint.mAxis = Eigen::Vector3d::UnitX();
    joint.mName = "u" + std::to_string(i);
    ::dart::dynamics::BodyNode::Properties body;
    body.mName = "floor" + std::to_string(i);
    auto [j, b] = skel->createJointAndBodyNodePair<::dart::dynamics::PrismaticJoint>(nullptr, joint, body);
    const double m = md_.m(i);
    b->setMass(m);
    b->setMomentOfInertia(m, m, m);  // never matters: nothing turns
    joints_.push_back(j);
    bodies_.push_back(b);
    if (world_->addSkeleton(skel).empty()) throw std::runtime_error("DART refused a skeleton");
    skeletons_.push_back(std::move(skel));
  }

  const BuildingModel& md_;
  Config config_;
  double gamma_h_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> smooth_;
  Eigen::VectorXd x_, f_;
  ::dart::simulation::WorldPtr world_;
  std::vector<::dart::dynamics::SkeletonPtr> skeletons_;
  std::vector<::dart::dynamics::Joint*> joints_;
  std::vector<::dart::dynamics::BodyNode*> bodies_;
  std::vector<std::shared_ptr<GapConstraint>> gaps_;
  std::vector<char> was_active_;
  LcpSolvers lcp_;
  long messages_before_ = 0;
  RunLimit& limit_;
};

}  // namespace

}  // namespace floors_faithful

std::unique_ptr<FloorsEngine> make_faithful_floors(const BuildingModel& md, const Config& config, const Settings& set,
                                                   double h, RunLimit& limit) {
  return std::make_unique<floors_faithful::Faithful>(md, config, set, h, limit);
}

}  // namespace pb::dart
