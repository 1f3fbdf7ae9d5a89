// The default variant on the buildings scene (buildings.hpp): what a DART user builds for
// shear buildings, with DART's own elements where it has them.
//
//   units     the suite's normalisation, as the single oscillators' default (default_model.cpp):
//             lengths in a_p / w_p^2, times in 1 / w_p, masses in floor 1's of building 0, so
//             that DART's compiled-in thresholds (no bounce below 0.1, push-out capped at 1e-3)
//             are fractions of the pulse's scales.
//   bodies    a skeleton per building, a chain of PrismaticJoints along x: floor 1 on the world,
//             floor i on floor i - 1 (its coordinate is the storey's drift), 2 box sizes above
//             it so that floors of different levels never touch. Each joint carries the storey's
//             spring k_i and, for Rayleigh damping, the storey's dashpot a1 k_i: DART's joint
//             spring and damper, integrated implicitly (C's a1 K part is exactly these dashpots).
//   forces    what no joint element carries, as external forces at the step's start: the
//             ground load -m_i a_g(t_k), and the rest of C: -a0 m_i v_i (Rayleigh), or the
//             whole -(C v)_i of a modal C, which couples every floor of a building.
//   contacts  a unit box (FCL's, DART's default collision detector) on every floor that has a
//             contact, the buildings side by side delta apart; restitution eps on each shape
//             (DART multiplies the two), friction DART's default; FCL's points at overlap, each
//             a ContactConstraint. Floors without a contact have no shape.
//   solver    DART's default: BoxedLcpConstraintSolver, Dantzig falling back to PGS (30 sweeps).

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/SparseCore>
#include <dart/collision/CollisionObject.hpp>
#include <dart/collision/CollisionResult.hpp>
#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/PrismaticJoint.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/simulation/World.hpp>

#include "solvers/dart/buildings_models.hpp"
#include "solvers/dart/lcp.hpp"

namespace pb::dart {

// Named, not anonymous: a unity build puts this file beside default_model.cpp.
namespace floors_default {

namespace {

using ::dart::dynamics::BodyNode;

constexpr double kBox = 1.0;     // every floor's box: a unit cube of the normalised length
constexpr double kLevel = 2.0;   // the height between two floors' boxes

class Default : public FloorsEngine {
 public:
  Default(const BuildingModel& md, double h, RunLimit& limit)
      : FloorsEngine(md), md_(md), length_(md.length_scale()), time_(1.0 / md.w_p), mass_(md.m(0)),
        touching_(md.contacts.size(), 0), now_(md.contacts.size(), 0), limit_(limit) {
    const int n = md.n_floors;
    rayleigh_ = md.scene.damping == BuildingDamping::rayleigh;
    a0_.assign(md.scene.buildings.size(), 0.0);
    // The modal C in the normalised units (mass / time), for the external -(C v).
    if (!rayleigh_) c_ = (md.C * (time_ / mass_)).sparseView();
    v_n_.setZero(n);
    f_n_.setZero(n);
    std::vector<char> shaped(static_cast<std::size_t>(n), 0);
    for (std::size_t j = 0; j < md.contacts.size(); ++j) {
      const FloorContact& fc = md.contacts[j];
      shaped[static_cast<std::size_t>(fc.i_left)] = shaped[static_cast<std::size_t>(fc.i_right)] = 1;
      contact_of_[{fc.i_left, fc.i_right}] = static_cast<int>(j);
    }
    prepare_process();
    world_ = ::dart::simulation::World::create("buildings");
    world_->setGravity(Eigen::Vector3d::Zero());
    world_->setTimeStep(h / time_);
    lcp_.dantzig = std::make_shared<CountingDantzig>();
    lcp_.pgs = std::make_shared<CountingPgs>();
    lcp_.dantzig->limit = lcp_.pgs->limit = &limit;
    world_->setConstraintSolver(std::make_unique<::dart::constraint::BoxedLcpConstraintSolver>(lcp_.dantzig, lcp_.pgs));
    const double spacing = kBox + md.scene.delta / length_;
    for (std::size_t b = 0; b < md.scene.buildings.size(); ++b)
      add_building(b, static_cast<double>(b) * spacing, shaped);
    messages_before_ = lcp_messages();
  }

  bool step(long k, double a_g, buildings::BuildingsResult& r) override {
    const double a = a_g * time_ * time_ / length_;
    const int n = md_.n_floors;
    for (int i = 0; i < n; ++i) v_n_(i) = v_[static_cast<std::size_t>(i)] * time_ / length_;
    if (rayleigh_)
      for (int i = 0; i < n; ++i)
        f_n_(i) = -a0_[static_cast<std::size_t>(md_.building_of[static_cast<std::size_t>(i)])] * md_.m(i) / mass_ * v_n_(i);
    else
      f_n_.noalias() = -(c_ * v_n_);
    for (int i = 0; i < n; ++i) {
      const double f = f_n_(i) - md_.m(i) / mass_ * a;
      if (!std::isfinite(f)) {
        r.status = Status::nan;
        r.message = "non-finite force at step " + std::to_string(k + 1);
        return false;
      }
      bodies_[static_cast<std::size_t>(i)]->addExtForce(Eigen::Vector3d(f, 0.0, 0.0));
    }
    limit_.tick();
    world_->step();
    // The chain's coordinates are drifts: a floor's displacement is their sum up to it.
    for (std::size_t b = 0; b < md_.scene.buildings.size(); ++b) {
      double u = 0.0, v = 0.0;
      const int first = md_.first[b];
      for (int i = 0; i < md_.scene.buildings[b].floors(); ++i) {
        const auto g = static_cast<std::size_t>(first + i);
        u += joints_[g]->getPosition(0);
        v += joints_[g]->getVelocity(0);
        u_[g] = u * length_;
        v_[g] = v * length_ / time_;
      }
    }
    collect_contacts();
    return true;
  }

  void finish(buildings::BuildingsResult& r) override {
    if (lcp_.pgs->calls > 0)
      add_note(r, "Dantzig's LCP failed in " + std::to_string(lcp_.pgs->calls) +
                      " steps and PGS took over (DART's fallback), " + std::to_string(lcp_.pgs->failures) +
                      " of them unconverged at its 30 sweeps");
    if (const long m = lcp_messages() - messages_before_; m > 0)
      add_note(r, "DART's LCP warned " + std::to_string(m) + " times");
  }

 private:
  void add_building(std::size_t b, double x, const std::vector<char>& shaped) {
    const Building& bl = md_.scene.buildings[b];
    double a0 = 0.0, a1 = 0.0;
    if (rayleigh_) {
      const BuildingModes& modes = md_.modes[b];
      rayleigh_coefficients(md_.scene.xi, modes.w(0), bl.floors() > 1 ? modes.w(1) : modes.w(0), a0, a1);
      a0_[b] = a0 * time_;
    }
    auto skel = ::dart::dynamics::Skeleton::create("building" + std::to_string(b));
    BodyNode* parent = nullptr;
    for (int i = 0; i < bl.floors(); ++i) {
      limit_.tick();
      const auto g = static_cast<std::size_t>(md_.first[b] + i);
      ::dart::dynamics::PrismaticJoint::Properties joint;
      joint.mAxis = Eigen::Vector3d::UnitX();
      joint.mName = "drift" + std::to_string(g);  // DART prints a note for every name it must make unique
      joint.mT_ParentBodyToJoint.translation() = Eigen::Vector3d(i == 0 ? x : 0.0, kLevel, 0.0);
      ::dart::dynamics::BodyNode::Properties node;
      node.mName = "floor" + std::to_string(g);
      auto [j, body] = skel->createJointAndBodyNodePair<::dart::dynamics::PrismaticJoint>(parent, joint, node);
      const double m = md_.m(static_cast<Eigen::Index>(g)) / mass_;
      body->setMass(m);
      body->setMomentOfInertia(m, m, m);
      const double k = bl.stiffnesses[static_cast<std::size_t>(i)];
      j->setSpringStiffness(0, k * time_ * time_ / mass_);
      j->setDampingCoefficient(0, a1 * k * time_ / mass_);
      if (shaped[g]) {
        auto* shape = body->createShapeNodeWith<::dart::dynamics::CollisionAspect, ::dart::dynamics::DynamicsAspect>(
            std::make_shared<::dart::dynamics::BoxShape>(Eigen::Vector3d::Constant(kBox)));
        shape->getDynamicsAspect()->setRestitutionCoeff(md_.scene.eps);
      }
      floor_of_[body] = static_cast<int>(g);
      joints_.push_back(j);
      bodies_.push_back(body);
      parent = body;
    }
    if (world_->addSkeleton(skel).empty()) throw std::runtime_error("DART refused a skeleton");
    skeletons_.push_back(std::move(skel));
  }

  // Per contact of the scene: whether FCL found its two floors' boxes touching at the step's
  // start (the collision DART's step solved), and whether that is new.
  void collect_contacts() {
    std::fill(now_.begin(), now_.end(), 0);
    for (const ::dart::collision::Contact& c : world_->getLastCollisionResult().getContacts()) {
      const BodyNode* first = c.collisionObject1->getShapeFrame()->asShapeNode()->getBodyNodePtr().get();
      const BodyNode* second = c.collisionObject2->getShapeFrame()->asShapeNode()->getBodyNodePtr().get();
      const int a = floor_of_.at(first), b = floor_of_.at(second);
      const auto it = contact_of_.find({std::min(a, b), std::max(a, b)});
      if (it != contact_of_.end()) now_[static_cast<std::size_t>(it->second)] = 1;
    }
    for (std::size_t j = 0; j < now_.size(); ++j) {
      entered_[j] = now_[j] && !touching_[j] ? 1 : 0;
      touching_[j] = now_[j];
    }
  }

  const BuildingModel& md_;
  double length_, time_, mass_;  // the model's units
  bool rayleigh_ = true;
  std::vector<double> a0_;                     // per building: Rayleigh's a0, normalised
  Eigen::SparseMatrix<double, Eigen::RowMajor> c_;  // a modal C, normalised
  Eigen::VectorXd v_n_, f_n_;
  ::dart::simulation::WorldPtr world_;
  std::vector<::dart::dynamics::SkeletonPtr> skeletons_;
  std::vector<::dart::dynamics::Joint*> joints_;  // per global floor
  std::vector<BodyNode*> bodies_;                 // per global floor
  std::map<const BodyNode*, int> floor_of_;
  std::map<std::pair<int, int>, int> contact_of_;  // (left floor, right floor) -> contact
  std::vector<char> touching_, now_;
  LcpSolvers lcp_;
  long messages_before_ = 0;
  RunLimit& limit_;
};

}  // namespace

}  // namespace floors_default

std::unique_ptr<FloorsEngine> make_default_floors(const BuildingModel& md, double h, RunLimit& limit) {
  return std::make_unique<floors_default::Default>(md, h, limit);
}

}  // namespace pb::dart
