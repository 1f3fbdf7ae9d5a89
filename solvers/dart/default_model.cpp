// The default variant: what a new DART user builds for the scene (solvers/dart/README.md).
//
//   units     the suite's normalisation: lengths in a_p / w_p^2, times in 1 / w_p, masses in
//             m0, so that DART's compiled-in thresholds (bounce below 0.1, push-out capped at
//             1e-3) are read as fractions of the pulse's scales and Pi1 is a function of the
//             Pi terms alone.
//   bodies    a skeleton per building: a BodyNode on a PrismaticJoint along x, a unit box
//             (FCL's, DART's default collision detector) at x = i (1 + delta), the joint's own
//             spring and damper (DART integrates them implicitly); the wall a box on a
//             WeldJoint. No gravity: it would act across the joints' axis.
//   restitution  eps on every shape: DART multiplies the two shapes' coefficients.
//   load      -m a_g(t_k) as the joint's force at the step's start.
//   solver    DART's default: BoxedLcpConstraintSolver, Dantzig falling back to PGS (30 sweeps).
//   contacts  FCL's at overlap, up to a dozen points per face pair, each a ContactConstraint
//             with DART's default friction 1 (two friction rows the joints make idle).

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <dart/collision/CollisionObject.hpp>
#include <dart/collision/CollisionResult.hpp>
#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/PrismaticJoint.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/dynamics/WeldJoint.hpp>
#include <dart/simulation/World.hpp>

#include "solvers/dart/engines.hpp"
#include "solvers/dart/lcp.hpp"

namespace pb::dart {

namespace {

using ::dart::dynamics::BodyNode;
using ::dart::dynamics::BoxShape;
using ::dart::dynamics::CollisionAspect;
using ::dart::dynamics::DynamicsAspect;
using ::dart::dynamics::ShapeNode;

// The box every building and the wall are: a unit cube of the normalised length.
constexpr double kBox = 1.0;

class Default : public StepEngine {
 public:
  Default(const System& sys, double h, RunLimit& limit)
      : StepEngine(sys), sys_(sys), load_(sys.pulse), length_(sys.length_scale()), time_(1.0 / sys.pulse.w),
        mass_(sys.bodies[ix(sys.ref)].m), h_(h), touching_(ix(sys.n_contacts()), 0), limit_(limit) {
    prepare_process();
    world_ = ::dart::simulation::World::create("pounding");
    world_->setGravity(Eigen::Vector3d::Zero());
    world_->setTimeStep(h / time_);
    // DART's own default (World's constructor makes the same), with counters.
    lcp_.dantzig = std::make_shared<CountingDantzig>();
    lcp_.pgs = std::make_shared<CountingPgs>();
    lcp_.dantzig->limit = lcp_.pgs->limit = &limit;
    world_->setConstraintSolver(std::make_unique<::dart::constraint::BoxedLcpConstraintSolver>(lcp_.dantzig, lcp_.pgs));
    const double spacing = kBox + sys.delta / length_;
    if (sys.wall) add_wall(-spacing);
    for (int i = 0; i < sys.n_bodies(); ++i) {
      limit.tick();
      add_building(i, static_cast<double>(i) * spacing);
    }
    messages_before_ = lcp_messages();
  }

  StepOutcome step(long k, Result& res) override {
    const double a_g = load_.accel(static_cast<double>(k) * h_) * time_ * time_ / length_;
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      const double f = -sys_.bodies[i].m / mass_ * a_g;
      if (!std::isfinite(f)) {
        res.status = Status::nan;
        res.message = "non-finite force";
        return StepOutcome::refused;
      }
      joints_[i]->setForce(0, f);
    }
    if (!step_within(*world_, limit_, k, h_, res)) return StepOutcome::refused;
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      out_.u[i] = joints_[i]->getPosition(0) * length_;
      out_.v[i] = joints_[i]->getVelocity(0) * length_ / time_;
    }
    collect_contacts();
    return StepOutcome::taken;
  }

  void finish(Result& res) override {
    if (lcp_.pgs->calls > 0)
      res.message += std::string(res.message.empty() ? "" : "; ") + "Dantzig's LCP failed in " +
                     std::to_string(lcp_.pgs->calls) + " steps and PGS took over (DART's fallback), " +
                     std::to_string(lcp_.pgs->failures) + " of them unconverged at its 30 sweeps";
    if (const long m = lcp_messages() - messages_before_; m > 0)
      res.message += std::string(res.message.empty() ? "" : "; ") + "DART's LCP warned " + std::to_string(m) + " times";
  }

 private:
  ShapeNode* add_box(BodyNode* body) {
    ShapeNode* shape =
        body->createShapeNodeWith<CollisionAspect, DynamicsAspect>(std::make_shared<BoxShape>(Eigen::Vector3d::Constant(kBox)));
    shape->getDynamicsAspect()->setRestitutionCoeff(sys_.eps);
    return shape;
  }

  void add_wall(double x) {
    auto skel = ::dart::dynamics::Skeleton::create("wall");
    ::dart::dynamics::WeldJoint::Properties joint;
    joint.mT_ParentBodyToJoint.translation() = Eigen::Vector3d(x, 0.0, 0.0);
    auto pair = skel->createJointAndBodyNodePair<::dart::dynamics::WeldJoint>(nullptr, joint);
    add_box(pair.second);
    body_index_[pair.second] = kWall;
    add(skel);
  }

  void add_building(int i, double x) {
    const Body& b = sys_.bodies[ix(i)];
    auto skel = ::dart::dynamics::Skeleton::create("building" + std::to_string(i));
    ::dart::dynamics::PrismaticJoint::Properties joint;
    joint.mAxis = Eigen::Vector3d::UnitX();
    joint.mT_ParentBodyToJoint.translation() = Eigen::Vector3d(x, 0.0, 0.0);
    auto [j, body] = skel->createJointAndBodyNodePair<::dart::dynamics::PrismaticJoint>(nullptr, joint);
    const double m = b.m / mass_;
    body->setMass(m);
    body->setMomentOfInertia(m, m, m);
    j->setSpringStiffness(0, b.k * time_ * time_ / mass_);
    j->setDampingCoefficient(0, b.c * time_ / mass_);
    j->setPosition(0, out_.u[ix(i)] / length_);
    j->setVelocity(0, out_.v[ix(i)] * time_ / length_);
    add_box(body);
    body_index_[body] = i;
    joints_.push_back(j);
    add(skel);
  }

  void add(const ::dart::dynamics::SkeletonPtr& skel) {
    if (world_->addSkeleton(skel).empty()) throw std::runtime_error("DART refused a skeleton");
    skeletons_.push_back(skel);
  }

  // The scene's contact between two bodies (kWall for the wall) that touch, or -1.
  int contact_of(int a, int b) const {
    const int left = std::min(a, b), right = std::max(a, b);
    if (right != left + 1) return -1;
    return sys_.wall ? right : left;
  }

  // Per contact of the scene: the x force on its right body, summed over FCL's points, and
  // whether it is new.
  void collect_contacts() {
    std::vector<double>& force = out_.force;
    std::fill(force.begin(), force.end(), 0.0);
    std::vector<char> now(touching_.size(), 0);
    const double force_unit = mass_ * length_ / (time_ * time_);
    for (const ::dart::collision::Contact& c : world_->getLastCollisionResult().getContacts()) {
      const BodyNode* first = c.collisionObject1->getShapeFrame()->asShapeNode()->getBodyNodePtr().get();
      const BodyNode* second = c.collisionObject2->getShapeFrame()->asShapeNode()->getBodyNodePtr().get();
      const int a = body_index_.at(first), b = body_index_.at(second);
      const int j = contact_of(a, b);
      if (j < 0) continue;
      now[ix(j)] = 1;
      // Contact::force acts on the first object's body.
      force[ix(j)] += (a > b ? c.force.x() : -c.force.x()) * force_unit;
    }
    for (std::size_t j = 0; j < now.size(); ++j) {
      out_.entered[j] = now[j] && !touching_[j] ? 1 : 0;
      touching_[j] = now[j];
    }
  }

  const System& sys_;
  LoadCursor load_;
  double length_, time_, mass_;  // the model's units
  double h_;
  ::dart::simulation::WorldPtr world_;
  std::vector<::dart::dynamics::SkeletonPtr> skeletons_;
  std::vector<::dart::dynamics::Joint*> joints_;
  std::map<const BodyNode*, int> body_index_;
  std::vector<char> touching_;
  LcpSolvers lcp_;
  long messages_before_ = 0;
  RunLimit& limit_;
};

}  // namespace

std::unique_ptr<StepEngine> make_default(const System& sys, const Config&, double h, RunLimit& limit) {
  return std::make_unique<Default>(sys, h, limit);
}

}  // namespace pb::dart
