// The faithful variants: ODE's faithful scheme in DART (solvers/dart/README.md).
//
//   bodies    a skeleton per building: a BodyNode of mass m_i on a PrismaticJoint along x
//             from the world, at the origin (the joint coordinate is u_i, the gaps are this
//             code's), no shapes, no gravity, no joint spring or damper.
//   forces    -k u - c v - m a_g(t_k) at the step's start as the joint's force: DART steps
//             v += h M^-1 F, then solves its constraints, then x += h v_new (World::step),
//             semi-implicit Euler with explicit springs, ODE's step.
//   contacts  a GapConstraint per contact, armed each step by the activation rule from the
//             state at the step's start, with the target eps max(0, -g'_k).
//   lcp       BoxedLcpConstraintSolver with Dantzig's solver or PGS and no fallback; a
//             Dantzig failure ends the run failed, as ODE's does.

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/PrismaticJoint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/simulation/World.hpp>

#include "solvers/dart/engines.hpp"
#include "solvers/dart/gap_constraint.hpp"
#include "solvers/dart/lcp.hpp"

namespace pb::dart {

namespace {

class Faithful : public StepEngine {
 public:
  Faithful(const System& sys, const Config& config, const Settings& set, double h, RunLimit& limit)
      : StepEngine(sys), sys_(sys), load_(sys.pulse), config_(config), h_(h), gamma_h_(set.gamma * h),
        was_active_(ix(sys.n_contacts()), 0), limit_(limit) {
    prepare_process();
    world_ = ::dart::simulation::World::create("pounding");
    world_->setGravity(Eigen::Vector3d::Zero());
    world_->setTimeStep(h);
    lcp_ = set_faithful_solver(*world_, config.lcp == Lcp::pgs, kFaithfulPgsSweeps, limit);
    add_bodies();
    for (int j = 0; j < sys.n_contacts(); ++j) {
      const int left = sys.left(j);
      auto gap =
          std::make_shared<GapConstraint>(left == kWall ? nullptr : bodies_[ix(left)], bodies_[ix(sys.right(j))], limit);
      world_->getConstraintSolver()->addConstraint(gap);
      gaps_.push_back(std::move(gap));
    }
    messages_before_ = lcp_messages();
  }

  StepOutcome step(long k, Result& res) override {
    const double a_g = load_.accel(static_cast<double>(k) * h_);
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      const Body& b = sys_.bodies[i];
      const double f = -b.k * out_.u[i] - b.c * out_.v[i] - b.m * a_g;
      if (!std::isfinite(f)) {
        res.status = Status::nan;
        res.message = "non-finite force";
        return StepOutcome::refused;
      }
      joints_[i]->setForce(0, f);
    }
    for (int j = 0; j < sys_.n_contacts(); ++j) {
      const auto jj = ix(j);
      const double g = sys_.gap(j, out_.u.data()), rate = sys_.gap_rate(j, out_.v.data());
      const bool on = active(config_.activation, g, rate, gamma_h_);
      // ODE's bounce: only an approach (g' < 0) rebounds, at eps times its speed.
      gaps_[jj]->arm(on, rate < 0.0 ? -sys_.eps * rate : 0.0);
      out_.entered[jj] = on && !was_active_[jj] ? 1 : 0;
      was_active_[jj] = on ? 1 : 0;
    }
    const long failures_before = lcp_.dantzig ? lcp_.dantzig->failures : 0;
    if (!step_within(*world_, limit_, k, h_, res)) return StepOutcome::refused;
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      out_.u[i] = joints_[i]->getPosition(0);
      out_.v[i] = joints_[i]->getVelocity(0);
    }
    for (std::size_t j = 0; j < gaps_.size(); ++j) out_.force[j] = gaps_[j]->impulse() / h_;
    if (lcp_.dantzig && lcp_.dantzig->failures != failures_before) return dantzig_gave_up("DART", k, "impulses", res);
    return StepOutcome::taken;
  }

  void finish(Result& res) override {
    if (lcp_.pgs && lcp_.pgs->failures > 0)
      res.message += std::string(res.message.empty() ? "" : "; ") + "PGS stopped at its " +
                     std::to_string(kFaithfulPgsSweeps) + " sweeps unconverged in " +
                     std::to_string(lcp_.pgs->failures) + " steps";
    if (const long m = lcp_messages() - messages_before_; m > 0)
      res.message += std::string(res.message.empty() ? "" : "; ") + "DART's LCP warned " + std::to_string(m) + " times";
  }

 private:
  // A skeleton per building (gap_constraint.hpp says why).
  void add_bodies() {
    for (std::size_t i = 0; i < sys_.bodies.size(); ++i) {
      limit_.tick();
      auto skel = ::dart::dynamics::Skeleton::create("building" + std::to_string(i));
      ::dart::dynamics::PrismaticJoint::Properties joint;
      joint.mAxis = Eigen::Vector3d::UnitX();
      joint.mName = "u" + std::to_string(i);
      ::dart::dynamics::BodyNode::Properties body;
      body.mName = "body" + std::to_string(i);
      auto [j, b] = skel->createJointAndBodyNodePair<::dart::dynamics::PrismaticJoint>(nullptr, joint, body);
      const double m = sys_.bodies[i].m;
      b->setMass(m);
      b->setMomentOfInertia(m, m, m);  // never matters: nothing turns
      j->setPosition(0, out_.u[i]);
      j->setVelocity(0, out_.v[i]);
      joints_.push_back(j);
      bodies_.push_back(b);
      if (world_->addSkeleton(skel).empty()) throw std::runtime_error("DART refused a skeleton");
      skeletons_.push_back(std::move(skel));
    }
  }

  const System& sys_;
  LoadCursor load_;  // a_g at each step's start, O(1) on a record
  Config config_;
  double h_;
  double gamma_h_;
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

std::unique_ptr<StepEngine> make_faithful(const System& sys, const Config& config, const Settings& set, double h,
                                          RunLimit& limit) {
  return std::make_unique<Faithful>(sys, config, set, h, limit);
}

}  // namespace pb::dart
