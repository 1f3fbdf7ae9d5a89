#pragma once
// The bilinear law with kinematic hardening of a yielding body (cases/README.md,
// "Yielding") as a time-stepper takes it: the implicit return map of one step. From the
// hysteretic variable z_n at the step's start and the step's displacement du, the trial
// z_n + du is clamped to [-u_y, u_y]; the restoring force is alpha k u + (1 - alpha) k z and
// its slope in u is k inside and alpha k where the map clamped. An elastic body (u_y
// infinite) never clamps: its force is k u to the last bit when alpha is 0 (z = u).
// Every time-stepper that applies the spring force itself applies this one (moreau-jean's
// own loop, yielding.cpp, writes the same map into its step's branches).

#include <algorithm>
#include <vector>

#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb {

struct Hysteresis {
  double z = 0.0;        // the hysteretic variable at the step's end
  double force = 0.0;    // alpha k u + (1 - alpha) k z
  double tangent = 0.0;  // d force / du: k, or alpha k where the map clamped
  double plastic = 0.0;  // the travel the map removed (trial - z): zero on the elastic branch
};

inline Hysteresis return_map(const Body& b, double alpha, double z_n, double u, double du) {
  if (!b.yields()) return {u, b.k * u, b.k, 0.0};
  const double trial = z_n + du;
  Hysteresis h;
  h.z = std::clamp(trial, -b.u_y, b.u_y);
  h.plastic = trial - h.z;
  h.force = alpha * b.k * u + (1.0 - alpha) * b.k * h.z;
  h.tangent = h.plastic == 0.0 ? b.k : alpha * b.k;
  return h;
}

// What a time-stepper measures of yielding (Result::residual, Result::hysteretic): the
// ground's work on every body and what body ref's hysteresis dissipated, step by step.
struct HystereticTally {
  double input = 0.0, dissipated = 0.0;
  // A step of body i: its mass, the step mean of a_g, its displacement over the step, and
  // its return map at the step's end.
  void step(const System& s, int i, double a_g_mean, double du, const Hysteresis& map) {
    const Body& b = s.bodies[static_cast<std::size_t>(i)];
    input -= b.m * a_g_mean * du;
    if (i == s.ref) dissipated += (1.0 - s.alpha) * b.k * map.z * map.plastic;
  }
  void finish(const System& s, double u_ref, double z_ref, Result& r) const {
    r.residual = s.residual(u_ref, z_ref);
    r.hysteretic = dissipated / input;
  }
};

// The springs of an engine that applies them as forces at the state of each step's start (ODE,
// Bullet): body i's force at u is the return map from the state it was last given to u,
// committed as it is applied. With no yielding body, k u, as before, to the last bit.
class StepSprings {
 public:
  StepSprings(const System& s, const std::vector<double>& u0)
      : sys_(s), yields_(s.yields()), z_(u0), u_(u0), a_g_(u0.size(), 0.0) {}

  // Body i's spring force at u, where the ground's acceleration over the coming step is a_g.
  double force(int i, double u, double a_g) {
    const Body& b = sys_.bodies[static_cast<std::size_t>(i)];
    if (!yields_) return b.k * u;
    const auto x = static_cast<std::size_t>(i);
    const Hysteresis map = return_map(b, sys_.alpha, z_[x], u, u - u_[x]);
    tally_.step(sys_, i, a_g_[x], u - u_[x], map);
    z_[x] = map.z;
    u_[x] = u;
    a_g_[x] = a_g;
    return map.force;
  }

  // The yielding responses from the final state u (one value per body); none without yield.
  void finish(const double* u, Result& r) {
    if (!yields_) return;
    for (int i = 0; i < sys_.n_bodies(); ++i) (void)force(i, u[i], 0.0);
    tally_.finish(sys_, u[sys_.ref], z_[static_cast<std::size_t>(sys_.ref)], r);
  }

 private:
  const System& sys_;
  bool yields_;
  std::vector<double> z_, u_, a_g_;  // per body, at the last state given
  HystereticTally tally_;
};

}  // namespace pb
