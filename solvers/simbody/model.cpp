// The Simbody model of a scene (model.hpp). Every call into Simbody is made inside a
// QuietScope (quiet_stdout.hpp): Debian's build prints a trace of every step on stdout.

#include "solvers/simbody/model.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Simbody.h>

#include "solvers/simbody/quiet_stdout.hpp"

namespace pb::simbody {

namespace {

using namespace SimTK;

std::size_t ix(int i) { return static_cast<std::size_t>(i); }

// The faithful variants' impulse solvers: an RMS constraint-velocity error of 1e-14 (round-off
// of O(1) velocities), at most 200 iterations (PGS: sweeps; PLUS: Newton steps).
constexpr Real kImpulseTolerance = 1e-14;
constexpr int kImpulseIterations = 200;

// PLUS's silent stretch with p contacts, in terms of seconds_per_term(): its numerical
// Jacobian is 2 p^3 terms, and a term there measured 4.0 to 6.4 times the calibration's (rows
// read across a column-major matrix that outgrows the caches, the index conversions): the
// stretch was 0.094, 0.54, 1.9 and 4.6 s at 100, 200, 300 and 400 contacts on a loaded 2-core
// machine, against 2 p^3 terms of 0.015, 0.13, 0.47 and 0.96 s.
constexpr double kSilentTerms = 8.0;

// The ground load -m a_g(t) on every body, at the time of the state it is realized at. It
// also notes the velocities the forces of time t_k are computed from (the stepper realizes
// them after its impacts: the dampers act at the post-impact velocities), for the impulses.
class GroundLoad : public Force::Custom::Implementation {
 public:
  GroundLoad(const std::vector<MobilizedBody>& bodies, const std::vector<double>& masses,
             std::function<double(double)> accel, const double* watch_time, std::vector<double>* seen)
      : bodies_(bodies), masses_(masses), accel_(std::move(accel)), watch_time_(watch_time), seen_(seen) {}

  void calcForce(const State& s, Vector_<SpatialVec>&, Vector_<Vec3>&, Vector& mobility) const override {
    const double a = accel_(s.getTime());
    for (std::size_t i = 0; i < bodies_.size(); ++i) bodies_[i].applyOneMobilityForce(s, 0, -masses_[i] * a, mobility);
    if (seen_ && s.getTime() == *watch_time_)
      for (std::size_t i = 0; i < bodies_.size(); ++i) (*seen_)[i] = bodies_[i].getOneU(s, 0);
  }
  Real calcPotentialEnergy(const State&) const override { return 0.0; }
  bool dependsOnlyOnPositions() const override { return false; }

 private:
  std::vector<MobilizedBody> bodies_;
  std::vector<double> masses_;
  std::function<double(double)> accel_;
  const double* watch_time_;
  std::vector<double>* seen_;
};

// The length along x between a link's two stations (ModelSpec::Link), in the model's units: a
// storey's drift moves the length by the drift itself, and the round-off of a length of 1e3 is
// 1e-13 a_p / w_p^2, far below any peak; a drift would have to reach -1e3 to turn the element.
constexpr Real kLink = 1e3;

// A damping matrix C on the bodies' coordinates: -(C v) at the velocities of the state it is
// realized at, as Simbody's dampers (the stepper realizes its forces after its impacts).
class DampingMatrix : public Force::Custom::Implementation {
 public:
  DampingMatrix(const std::vector<MobilizedBody>& bodies, const std::vector<double>& c) : bodies_(bodies), c_(c) {}

  void calcForce(const State& s, Vector_<SpatialVec>&, Vector_<Vec3>&, Vector& mobility) const override {
    const std::size_t n = bodies_.size();
    for (std::size_t i = 0; i < n; ++i) {
      double f = 0.0;
      for (std::size_t j = 0; j < n; ++j) f -= c_[i * n + j] * bodies_[j].getOneU(s, 0);
      bodies_[i].applyOneMobilityForce(s, 0, f, mobility);
    }
  }
  Real calcPotentialEnergy(const State&) const override { return 0.0; }
  bool dependsOnlyOnPositions() const override { return false; }

 private:
  std::vector<MobilizedBody> bodies_;
  std::vector<double> c_;
};

// When a contact takes part in a step: the faithful rule g + gamma h g' <= 0 from the state at
// the step's start (the stepper asks isProximal there), or the stepper's own, g <= its
// constraint tolerance. Either way the answer is noted for the step's counts, and the run's
// limit is asked (`watch`, ModelSpec::out_of_time).
struct Proximity {
  bool predicted = true;
  double gamma_h = 0.0;
  std::vector<char>* noted = nullptr;
  int index = 0;
  const std::function<void()>* watch = nullptr;

  bool takes(double g, double rate, Real ptol) const { return predicted ? g + gamma_h * rate <= 0.0 : g <= ptol; }
  bool decide(double g, double rate, Real ptol) const {
    if (watch) (*watch)();
    const bool on = takes(g, rate, ptol);
    (*noted)[ix(index)] = on ? 1 : 0;
    return on;
  }
};

// Seconds one term of PLUS's products of a matrix row and a packed column takes (its
// multRowTimesActiveCol: each term reads the row through SimTK's accessor, RowVectorView::
// operator[] into MatrixHelper::getElt, and the column likewise), measured on a 64 x 64
// matrix: the fastest of 4 passes, so that a moment's load does not inflate it.
double seconds_per_term() {
  const int n = 64;
  const Matrix a(n, n, 1.0);
  const Vector column(n, 1.0);
  Array_<int> active(n);
  for (int i = 0; i < n; ++i) active[i] = i;
  Real sum = 0.0;
  double best = Infinity;
  for (int pass = 0; pass < 4; ++pass) {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < n; ++r) {
      const RowVectorView row = a[r];
      for (int c = 0; c < n; ++c) sum += row[active[c]] * column[c];
    }
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  if (!(sum > 0.0)) return 0.0;  // never: the terms are used, so that none is optimised away
  return best / (n * n);
}

// The wall: a lower stop of body 0's coordinate at -delta (g = u + delta).
class WallStop : public HardStopLower {
 public:
  WallStop(MobilizedBody& body, Real delta, Real eps, Proximity rule)
      : HardStopLower(body, MobilizerQIndex(0), -delta, eps), body_(body), rule_(rule) {}
  bool isProximal(const State& s, Real ptol) const override {
    return rule_.decide(getPerr(s), body_.getOneU(s, 0), ptol);
  }

 private:
  MobilizedBody body_;
  Proximity rule_;
};

// Two bodies: the left one's plane x = -delta (normal +x) against the right one's origin, so
// that g = delta + u_R - u_L (every body's origin is the ground's at rest).
class BodyContact : public PointPlaneFrictionlessContact {
 public:
  BodyContact(MobilizedBody& left, MobilizedBody& right, Real delta, Real eps, Proximity rule)
      : PointPlaneFrictionlessContact(left, UnitVec3(1, 0, 0), -delta, right, Vec3(0), eps),
        left_(left), right_(right), rule_(rule) {}
  bool isProximal(const State& s, Real ptol) const override {
    return rule_.decide(getPerr(s), right_.getOneU(s, 0) - left_.getOneU(s, 0), ptol);
  }

 private:
  MobilizedBody left_, right_;
  Proximity rule_;
};

}  // namespace

struct Model::Impl {
  ModelSpec spec;
  MultibodySystem system;
  SimbodyMatterSubsystem matter{system};
  GeneralForceSubsystem forces{system};
  GeneralContactSubsystem contacts{system};
  std::vector<MobilizedBody> bodies;
  std::unique_ptr<SemiExplicitEulerTimeStepper> stepper;
  std::unique_ptr<RungeKuttaMersonIntegrator> integrator;
  double watch_time = 0.0;            // the time whose forces GroundLoad notes
  std::vector<double> u_seen;         // the velocities the step's forces saw
  std::vector<char> proximal;         // per contact, decided in the last step
  std::vector<ContactStep> steps;     // per contact, the last step's
  std::vector<double> q, u;           // per body, after the last step
  bool halted = false;                // out_of_time said so in this step
  double term_seconds = 0.0;          // seconds_per_term(), once measured
  // Asks the run's limit; once passed, tells the impulse solver to stop at its next iteration
  // (ImpulseSolver reads both settings at each: PLUS's Newton loop and active-set test, PGS's
  // sweeps), so that the step ends without converging and is thrown away.
  const std::function<void()> watch = [this] {
    if (halted || !spec.out_of_time || !spec.out_of_time()) return;
    halted = true;
    if (!stepper) return;
    auto& solver = const_cast<ImpulseSolver&>(stepper->getImpulseSolver());  // the stepper's own, made non-const
    solver.setConvergenceTol(Infinity);
    solver.setMaxIterations(1);
  };

  explicit Impl(const ModelSpec& s) : spec(s) {
    const int n = static_cast<int>(s.m.size());
    u_seen.assign(ix(n), 0.0);
    proximal.assign(s.left.size(), 0);
    steps.assign(s.left.size(), ContactStep{});
    for (int i = 0; i < n; ++i) {
      Body::Rigid body(MassProperties(s.m[ix(i)], Vec3(0), UnitInertia(1)));
      MobilizedBody::Slider slider(matter.Ground(), Transform(), body, Transform());
      bodies.push_back(slider);
      Force::MobilityLinearSpring(forces, slider, MobilizerQIndex(0), s.k[ix(i)], 0.0);
      Force::MobilityLinearDamper(forces, slider, MobilizerUIndex(0), s.c[ix(i)]);
    }
    for (const ModelSpec::Link& link : s.links) {
      const MobilizedBody& lower = link.lower < 0 ? matter.Ground() : bodies[ix(link.lower)];
      const MobilizedBody& upper = bodies[ix(link.upper)];
      Force::TwoPointLinearSpring(forces, lower, Vec3(-kLink, 0, 0), upper, Vec3(0), link.k, kLink);
      if (link.c != 0.0) Force::TwoPointLinearDamper(forces, lower, Vec3(-kLink, 0, 0), upper, Vec3(0), link.c);
    }
    if (!s.damping_matrix.empty()) Force::Custom(forces, new DampingMatrix(bodies, s.damping_matrix));
    const bool stepper_kind = s.kind != Kind::hunt_crossley;
    Force::Custom(forces, new GroundLoad(bodies, s.m, s.ground_accel, &watch_time, stepper_kind ? &u_seen : nullptr));
    if (stepper_kind)
      add_unilateral_contacts();
    else
      add_hunt_crossley_contacts();
    system.realizeTopology();
    State state = system.getDefaultState();
    for (int i = 0; i < n; ++i) {
      bodies[ix(i)].setOneQ(state, 0, s.u[ix(i)]);
      bodies[ix(i)].setOneU(state, 0, s.v[ix(i)]);
    }
    q = s.u;
    u = s.v;
    if (stepper_kind) {
      stepper = std::make_unique<SemiExplicitEulerTimeStepper>(system);
      if (s.kind != Kind::stepper_default) {
        stepper->setConstraintTolerance(s.constraint_tol);
        stepper->setPositionProjectionMethod(SemiExplicitEulerTimeStepper::NoPositionProjection);
        // The impulse solver the stepper would make, converged to round-off: PGS stops at an
        // RMS constraint-velocity error of 1e-6 by default (measured: restitution off by 2e-7),
        // PLUS at 1e-10.
        const Real rolling = stepper->getDefaultFrictionTransitionVelocityInUse();
        ImpulseSolver* solver = s.kind == Kind::faithful_pgs ? static_cast<ImpulseSolver*>(new PGSImpulseSolver(rolling))
                                                             : new PLUSImpulseSolver(rolling);
        solver->setConvergenceTol(kImpulseTolerance);
        solver->setMaxIterations(kImpulseIterations);
        stepper->setImpulseSolver(solver);
      }
      stepper->initialize(state);
    } else {
      integrator = std::make_unique<RungeKuttaMersonIntegrator>(system);
      integrator->setAccuracy(s.accuracy);
      // Every internal step is handed to the caller (Model::step), and a report ends a step
      // exactly: interpolating one copies the whole State, which cost 0.25 ms a report.
      integrator->setReturnEveryInternalStep(true);
      integrator->setAllowInterpolation(false);
      integrator->initialize(state);
    }
  }

  void add_unilateral_contacts() {
    const bool predicted = spec.kind != Kind::stepper_default;
    for (std::size_t j = 0; j < spec.left.size(); ++j) {
      const Proximity rule{predicted, spec.gamma * spec.h, &proximal, static_cast<int>(j), &watch};
      MobilizedBody& right = bodies[ix(spec.right[j])];
      if (spec.left[j] < 0)
        matter.adoptUnilateralContact(new WallStop(right, spec.delta, spec.eps, rule));
      else
        matter.adoptUnilateralContact(new BodyContact(bodies[ix(spec.left[j])], right, spec.delta, spec.eps, rule));
    }
  }

  // A contact set per contact (HuntCrossleyForce::calcForce returns at the first contact of
  // its set whose force is not positive, leaving the others of the set without force): the
  // right body's sphere of unit radius touching, at its leftmost point (the body's origin),
  // the left body's half-space x < -delta (the ground's for the wall). Both surfaces get the
  // same stiffness and dissipation, which Simbody combines to half the stiffness each.
  void add_hunt_crossley_contacts() {
    const double stiffness = 2.0 * std::pow(0.75 * spec.hertz, 2.0 / 3.0);  // (4/3) (s/2)^(3/2) = hertz
    // HalfSpace occupies x > 0 of its frame: turned about y by pi it occupies x < 0.
    const Transform half_space(Rotation(Pi, YAxis), Vec3(-spec.delta, 0, 0));
    for (std::size_t j = 0; j < spec.left.size(); ++j) {
      const ContactSetIndex set = contacts.createContactSet();
      const MobilizedBody& left = spec.left[j] < 0 ? matter.Ground() : bodies[ix(spec.left[j])];
      contacts.addBody(set, left, ContactGeometry::HalfSpace(), half_space);
      contacts.addBody(set, bodies[ix(spec.right[j])], ContactGeometry::Sphere(1.0), Transform(Vec3(1.0, 0, 0)));
      HuntCrossleyForce force(forces, contacts, set);
      for (int surface = 0; surface < 2; ++surface)
        force.setBodyParameters(ContactSurfaceIndex(surface), stiffness, spec.dissipation, 0.0, 0.0, 0.0);
    }
  }

  bool step(long k, const InternalStep& each) {
    const double t1 = static_cast<double>(k + 1) * spec.h;
    if (stepper)
      take_stepper_step(t1);
    else
      take_integrator_step(t1, each);
    return !halted;
  }

  int contacts_next_step() const {
    if (!stepper) return 0;
    const bool predicted = spec.kind != Kind::stepper_default;
    const Proximity rule{predicted, spec.gamma * spec.h};
    int n = 0;
    for (std::size_t j = 0; j < spec.left.size(); ++j) {
      const int l = spec.left[j];
      const auto r = ix(spec.right[j]);
      const double g = spec.delta + q[r] - (l < 0 ? 0.0 : q[ix(l)]);
      const double rate = u[r] - (l < 0 ? 0.0 : u[ix(l)]);
      if (rule.takes(g, rate, stepper->getConstraintToleranceInUse())) ++n;
    }
    return n;
  }

  double silent_seconds(int n_contacts) {
    if (!stepper || spec.kind == Kind::faithful_pgs || n_contacts < 16) return 0.0;  // below 16: 8192 terms
    if (term_seconds == 0.0) term_seconds = seconds_per_term();
    const double p = n_contacts;
    return kSilentTerms * p * p * p * term_seconds;
  }

  void take_stepper_step(double t1) {
    const State& before = stepper->getState();
    const double t0 = before.getTime();
    watch_time = t0;
    const std::vector<double> q0 = q, u0 = u;
    stepper->stepTo(t1);
    const State& after = stepper->getState();
    read(after);
    if (!spec.links.empty()) {  // the buildings: which contacts took part, not their impulses
      for (std::size_t j = 0; j < spec.left.size(); ++j) steps[j] = ContactStep{proximal[j] != 0, 0.0};
      return;
    }
    // The impulse each contact gave over the step, from each body's momentum balance:
    // m (u1 - u0) = h f + (impulses), f the spring at q0, the damper at the velocities the
    // stepper's forces saw, the ground load at t0; then contact by contact from the right
    // end of the row, where a body has one contact.
    const double h = after.getTime() - t0;
    const double a = spec.ground_accel(t0);
    double next = 0.0;  // the impulse of the contact to the right of this one
    for (std::size_t j = spec.left.size(); j-- > 0;) {
      const auto r = ix(spec.right[j]);
      const double f = -spec.k[r] * q0[r] - spec.c[r] * u_seen[r] - spec.m[r] * a;
      const double impulse = spec.m[r] * (u[r] - u0[r]) - h * f + next;
      ContactStep& out = steps[j];
      out.engaged = proximal[j] != 0;
      out.force = out.engaged ? impulse / h : 0.0;
      next = out.force * h;
    }
  }

  void take_integrator_step(double t1, const InternalStep& each) {
    while (integrator->getTime() < t1) {
      watch();
      if (halted) return;
      integrator->stepTo(t1);
      read(integrator->getState());
      if (each) each(integrator->getTime(), q.data(), u.data());
    }
    // The element's force at the report time, as HuntCrossleyForce computes it.
    for (std::size_t j = 0; j < spec.left.size(); ++j) {
      const int l = spec.left[j];
      const auto r = ix(spec.right[j]);
      const double x = -(spec.delta + q[r] - (l < 0 ? 0.0 : q[ix(l)]));  // penetration
      const double xdot = -(u[r] - (l < 0 ? 0.0 : u[ix(l)]));
      ContactStep& out = steps[j];
      out.engaged = x > 0.0;
      out.force = out.engaged ? std::max(0.0, spec.hertz * x * std::sqrt(x) * (1.0 + 1.5 * spec.dissipation * xdot)) : 0.0;
    }
  }

  void read(const State& s) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      q[i] = bodies[i].getOneQ(s, 0);
      u[i] = bodies[i].getOneU(s, 0);
    }
  }
};

Model::Model(const ModelSpec& spec) {
  const QuietScope quiet;
  try {
    impl_ = std::make_unique<Impl>(spec);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("Simbody: ") + e.what());
  }
}

Model::~Model() {
  const QuietScope quiet;
  impl_.reset();
}

bool Model::step(long k, const InternalStep& each) {
  const QuietScope quiet(&impl_->watch);
  try {
    return impl_->step(k, each);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("Simbody: ") + e.what());
  }
}

int Model::contacts_next_step() const {
  const QuietScope quiet;
  return impl_->contacts_next_step();
}

double Model::silent_seconds(int contacts) { return impl_->silent_seconds(contacts); }

double Model::u(int body) const { return impl_->q[ix(body)]; }
double Model::v(int body) const { return impl_->u[ix(body)]; }
const ContactStep& Model::contact(int j) const { return impl_->steps[ix(j)]; }

}  // namespace pb::simbody
