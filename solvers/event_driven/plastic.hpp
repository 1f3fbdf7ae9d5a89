#pragma once
// Yielding bodies in the reference (DERIVATION.md §10). A body's restoring force is
// bilinear with kinematic hardening, so between events it is linear on one of two branches:
// elastic, k u with the constant offset of its plastic drift, or yielding at z = +-u_y,
// alpha k u with a constant offset. Yielding and unloading are events, found like contacts
// (the frame's yield functions, first_root to an ulp); this class holds what they change
// and what the run measures of them: each body's branch (in State), where its yielding
// phase began, the hysteretic energy, and the ground's work and the dampers' by quadrature
// of the closed forms (the energy balance and the hysteretic share of the input).
//
// A system with no yielding body never reaches any of this: start() leaves its state and
// frame without branches, and the solver does not call the rest.

#include <vector>

#include "solvers/event_driven/frame.hpp"
#include "kit/run_limits.hpp"
#include "kit/solver.hpp"

namespace pb::event_driven {

struct YieldEvent {
  double t;  // NaN: none
  int body = -1;
  int side = 0;  // on the elastic branch: 0 yields at z = +u_y, 1 at z = -u_y; yielding: 0 (unloads)
};

class Plasticity {
 public:
  // Every body on its elastic branch with no plastic drift (z = 0 at rest), and the frame's
  // yield functions sized; for a system with no yielding body, no branches at all.
  void start(const System& s, State& st, Frame& fr);
  bool on() const { return on_; }

  // The first yield or unloading after st.t, before b (strictly: a contact's event at the
  // same time goes first, and settle() then sees the yield). noise_u and noise_v: the level
  // below which a neutral function (search.hpp, first_root) counts as crossed, for
  // displacements (u_y -+ z) and for velocities (s u').
  YieldEvent next(const System& s, const State& st, const Frame& fr, double b, double floor, double settle,
                  double noise_u, double noise_v, Deadline& deadline) const;

  // At a yield event: onto the yielding branch at z = s u_y, or off it, where its plastic
  // drift e = u - s u_y is set and the phase's hysteretic energy counted.
  void change(const System& s, State& st, const YieldEvent& event);

  // Where velocities have jumped (an impact, the start): a body at its yield limit (within
  // tol_u) moving outward faster than tol_v yields, a yielding one moving back unloads.
  void settle(const System& s, State& st, double tol_u, double tol_v);

  // The ground's work and the dampers' over [a, b], an interval without events, from the
  // frame's closed forms (Gauss-Legendre on panels of an eighth of the shortest period:
  // exact to round-off).
  void integrate(const System& s, const Frame& fr, double a, double b);

  // The mechanical energy of a state (System::energy with the hysteretic variables).
  double energy(const System& s, const State& st, const double* u, const double* v);

  // At the end of a run: the energy terms, body 0's residual displacement and its
  // hysteretic share of the input energy. impact_losses: what the events took (the
  // negative of the solver's energy balance of event jumps).
  void finish(const System& s, const State& st, double impact_losses, Result& r);

 private:
  bool on_ = false;
  std::vector<double> onset_;  // per body: u where its yielding phase began
  std::vector<double> z_;      // scratch for energy()
  double hysteretic_ = 0.0;    // every body's, over finished phases
  double hysteretic_ref_ = 0.0;
  double input_ = 0.0, damped_ = 0.0;

  // A yielding phase's dissipation (1 - alpha) k u_y |u - onset| (z stays at s u_y while u
  // moves outward), counted where it ends.
  void close_phase(const System& s, const State& st, int i);
};

}  // namespace pb::event_driven
