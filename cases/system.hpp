#pragma once
// The physical system a solver integrates, made from a Case by the Pi mapping of the
// paper (eq. 8), and the mapping back. This is the only place that mapping lives.
//
//   w0 = Pi2 w_p   delta = Pi3 a_p / w_p^2   eps = Pi4
//   w1 = w0 / Pi5  m1 = m0 / Pi6             w2 = w0 / Pi7   m2 = m0 / Pi8    (m0 = 1)
//
// Coordinates are displacements relative to the ground; every body starts at rest except
// body 0 of a chain, which moves at kick a_p / w_p (u_start, v_start hold the start). Bodies are stored left to right;
// contact j joins bodies left(j) and right(j) (left(j) == kWall for the wall, which moves
// with the ground), and its gap is g_j = delta + u[right(j)] - u[left(j)].
// Equation of motion: M u'' + C u' + K u = -M 1 a_g(t) + W lambda, lambda >= 0 on g = 0.

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "cases/case.hpp"
#include "cases/load.hpp"

namespace pb {

struct Body {
  double m;  // mass
  double w;  // natural circular frequency
  double k;  // m w^2
  double c;  // 2 xi m w
  // Yield displacement (cases/README.md, "Yielding"): infinity for an elastic body.
  double u_y = std::numeric_limits<double>::infinity();
  bool yields() const { return u_y < std::numeric_limits<double>::infinity(); }
};

inline constexpr int kWall = -1;

// Bodies and contacts are numbered by int, as a case numbers them; containers are indexed by
// std::size_t.
inline std::size_t ix(int i) { return static_cast<std::size_t>(i); }

struct System {
  std::vector<Body> bodies;  // left to right
  bool wall = false;         // a wall (fixed to the ground) left of bodies[0]
  int ref = 0;               // index of body 0, whose |u| gives Pi1
  double delta = 0.0;        // gap of every contact at rest
  double eps = 0.0;          // coefficient of restitution
  double xi = 0.05;          // damping ratio of every body
  double a_p = 1.0;          // pulse amplitude (unsigned); a record: the a_p of its Pi terms
  Pulse pulse;               // the ground acceleration (cases/load.hpp)
  double t_end = 0.0;  // the load's duration (T_p, a record's length) + n_free T_max
  double t_min = 0.0;  // min(T_p, shortest natural period): fixed steps are t_min / N
  std::vector<double> u_start, v_start;  // state at t = 0, one value per body
  // A yielding body's restoring force (Body::u_y finite) is bilinear with kinematic
  // hardening: r = alpha k u + (1 - alpha) k z, where z follows u (z' = u') while |z| < u_y
  // or while the body moves back from |z| = u_y, and stays at +-u_y while it moves on
  // outward. Every body starts at z = 0. Damping stays 2 xi m w.
  double alpha = 0.0;

  int n_bodies() const { return static_cast<int>(bodies.size()); }
  int n_contacts() const { return n_bodies() - 1 + (wall ? 1 : 0); }
  int left(int j) const { return wall ? j - 1 : j; }
  int right(int j) const { return wall ? j : j + 1; }
  // Gap of contact j in state u, and its rate in velocities v (one value per body).
  double gap(int j, const double* u) const {
    return delta + u[right(j)] - (left(j) == kWall ? 0.0 : u[left(j)]);
  }
  double gap_rate(int j, const double* v) const { return v[right(j)] - (left(j) == kWall ? 0.0 : v[left(j)]); }
  // The pulse's length scale a_p / w_p^2 (Pi3 and Pi1 are lengths over it).
  double length_scale() const { return a_p / (pulse.w * pulse.w); }
  // The length of a Hertz-type contact's stiffness (cases/README.md, "Contact stiffness"): the
  // pulse's a_p / w_p^2, physical for the paper's pulses and the pulse models; a record's own
  // (Record::length_scale), as its a_p and w_p are only the unit of its Pi terms. NaN for a
  // record with no Fourier amplitude between 0.25 and 20 Hz.
  double contact_length_scale() const { return pulse.record ? pulse.record->length_scale() : length_scale(); }
  double pi1(double u_max) const { return u_max / length_scale(); }
  // Fixed step of a time-stepper with N steps per shortest period.
  double step(int n) const { return t_min / n; }
  // Mechanical energy in the ground's frame: kinetic plus spring energy. The wall moves
  // with the ground, so contacts do no work in this frame except at impacts.
  double energy(const double* u, const double* v) const;
  // The same with the hysteretic variables z (one per body; an elastic body's is its u):
  // a yielding body stores alpha k u^2 / 2 + (1 - alpha) k z^2 / 2. An elastic body's
  // term is energy()'s, bit for bit.
  double energy(const double* u, const double* v, const double* z) const;
  // Whether any body yields.
  bool yields() const;
  // The residual displacement of body ref over a_p / w_p^2: where it comes to rest from
  // u, z (its last elastic branch's equilibrium, (1 - alpha) (u - z)); 0 for an elastic body.
  double residual(double u, double z) const;
  // What energy excesses are measured against: the start's energy plus the kinetic
  // energy of every body moving at a_p / w_p (the velocity scale of the pulse).
  double energy_scale() const;
};

// The Case must be valid (validate() returns nothing).
System make_system(const Case& c);

// The inverse mapping: the Pi terms of a physical system (family, n_free are not
// recoverable beyond what t_end implies; n_free is recomputed from t_end).
Case case_of(const System& s);

}  // namespace pb
