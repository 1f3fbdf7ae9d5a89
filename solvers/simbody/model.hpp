#pragma once
// The Simbody model of a scene and its stepping, behind an interface with no Simbody type:
// model.cpp alone includes Simbody's headers, and is compiled as C++17 (they are not valid
// C++20: ambiguous rewritten comparisons in ContactGeometry.h) and without NDEBUG (as Debian
// built the library: the layout of SimTK's State cache entries depends on it).
// Everything here is in the model's units (simbody_solver.cpp converts).

#include <functional>
#include <memory>
#include <vector>

namespace pb::simbody {

enum class Kind {
  faithful_plus,  // SemiExplicitEulerTimeStepper, PLUS impulse solver, predicted contacts
  faithful_pgs,   // the same with its PGS impulse solver
  stepper_default,  // SemiExplicitEulerTimeStepper with its own settings, contacts by its margin
  hunt_crossley,  // HuntCrossleyForce contacts, integrated by RungeKuttaMersonIntegrator
};

struct ModelSpec {
  Kind kind = Kind::faithful_plus;
  std::vector<double> m, k, c;   // per body, left to right
  std::vector<double> u, v;      // per body, at t = 0
  std::vector<int> left, right;  // per contact: its bodies (left -1: the wall)
  double delta = 0.0;            // the gap at rest
  double eps = 0.0;              // coefficient of restitution (minCOR of the unilateral contacts)
  std::function<double(double)> ground_accel;  // a_g(t)
  double h = 0.0;                // the step (steppers) or the output interval (hunt-crossley)
  double gamma = 0.5;            // faithful: the look-ahead of the predicted activation rule
  double constraint_tol = 1e-12;  // faithful: the stepper's constraint tolerance
  // hunt-crossley: the Hertz coefficient K of f = K x^(3/2) (1 + 1.5 c x'), the dissipation
  // c, and the integrator's accuracy.
  double hertz = 0.0;
  double dissipation = 0.0;
  double accuracy = 1e-8;
  // The buildings scene (buildings.cpp; empty for the single oscillators, whose k and c above
  // are each body's to the ground): a TwoPointLinearSpring of stiffness k and a
  // TwoPointLinearDamper of c between two bodies (lower -1: the ground), their stations kLink
  // apart along x so that the elements' line stays the x axis (the force is then k times the
  // two displacements' difference, exactly); and a damping matrix applied whole, -(C v), by a
  // Force::Custom (a modal C couples every floor of a building: no two-point element has it).
  struct Link {
    int lower = -1, upper = 0;
    double k = 0.0, c = 0.0;
  };
  std::vector<Link> links;
  std::vector<double> damping_matrix;  // n x n by rows; empty: none
  // The run's time limit: true once it has passed (or the sweep stops). Asked wherever a step
  // runs this project's code: each contact's isProximal, each internal step of hunt-crossley's
  // integrator, and each line of the trace Simbody writes (quiet_stdout.hpp), at every
  // iteration of its impulse solvers. Null: no limit.
  std::function<bool()> out_of_time;
};

// What a step did to a contact.
struct ContactStep {
  // steppers: a constraint of the step (proximal); hunt-crossley: penetrating at the step's end
  bool engaged = false;
  // steppers: its impulse over the step divided by the step (>= 0 pushes the bodies apart);
  // hunt-crossley: the element's force at the step's end
  double force = 0.0;
};

// hunt-crossley: called after every internal step of the integrator with its time and the
// bodies' positions and velocities.
using InternalStep = std::function<void(double t, const double* q, const double* u)>;

class Model {
 public:
  explicit Model(const ModelSpec& spec);  // throws std::runtime_error with Simbody's message
  ~Model();
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  // Advances from t_k = k h to (k + 1) h, calling `each` (if set) after every internal step.
  // false: ModelSpec::out_of_time said so during the step, and the model's state is not to be
  // used (a stepper's impulse solvers were told to stop at their next iteration, unconverged).
  bool step(long k, const InternalStep& each = nullptr);
  // The stepper variants: the contacts the next step takes (the rule isProximal applies, on
  // the state now). hunt-crossley: 0.
  int contacts_next_step() const;
  // Wall seconds the stepper's impulse solve of `contacts` proximal contacts spends in one
  // stretch that no trace line interrupts, or 0 where it has none (PGS, hunt-crossley).
  // PLUS (plus-faithful, default): Debian's build checks every Newton iteration's Jacobian
  // numerically, 2 p^3 terms of products of its p x p matrix's rows, silent: measured 1.9 s
  // at p = 300 on a loaded 2-core machine. Estimated from a term's time, measured once per
  // model (model.cpp, kSilentTerms).
  double silent_seconds(int contacts);
  double u(int body) const;
  double v(int body) const;
  const ContactStep& contact(int j) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pb::simbody
