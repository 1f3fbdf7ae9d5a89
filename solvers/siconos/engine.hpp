#pragma once
// The one place that touches Siconos: a run's model and simulation behind two small classes,
// one per integration, each hiding its Siconos objects (engine.cpp). The step loops, the
// counts and the Result are the callers' (time_stepping.cpp, event_driven.cpp).
//
// Why a separate layer: Siconos 4.4's headers need Boost 1.74's uBLAS, which does not compile
// as C++20 (it calls std::allocator::construct), so engine.cpp is compiled as C++17 and this
// header holds plain data only, in C++17.
//
// Everything here is in the pulse's units: lengths over a_p / w_p^2, times over 1 / w_p.
//
// Thread safety. Siconos keeps process-wide state: static counters written by every
// DynamicalSystem, Interaction and Event constructor; for LSODAR, ODEPACK's COMMON blocks and
// the one LsodarOSI that its Fortran callbacks reach. A TimeStepper is made (model,
// simulation, initialisation, which makes its events) and destroyed under a process-wide
// lock and steps without it; an EventDrivenRun holds the lock from construction to
// destruction (README, thread safety).

#include <memory>
#include <vector>

namespace pb::siconos::engine {

struct BodySpec {
  double m, k, c;  // mass, stiffness, damping
  double u0, v0;   // start state
};

struct ContactSpec {
  int left, right;  // bodies; left = -1: the wall
};

struct ModelSpec {
  std::vector<BodySpec> bodies;       // left to right
  std::vector<ContactSpec> contacts;  // gap y = delta + u[right] - u[left]
  double delta = 0.0, eps = 0.0;
  bool cosine = false;      // a_g = amplitude cos t, else amplitude sin t, for 0 <= t <= 2 pi
  double amplitude = 1.0;   // +-1
  double sample_step = 0.0;  // the load plugin samples a_g by Pulse::sample(t, sample_step)
  double t_end = 0.0;
};

// a_g in the pulse's units, sampled as Pulse::sample(t, step) does (defined with Pulse, in
// model.cpp): what the load plugin gives Siconos.
double ground_sample(bool cosine, double amplitude, double t, double step);

// What the dense LCP driver met on a step: its q's sign and size, and whether the solver's
// iteration counter was written (only a call of Lemke or enumeration writes it).
struct LcpCall {
  bool called = false;       // a contact was active: the driver ran
  bool q_nonnegative = false;
  int rows = 0;
  bool counter_written = false;
  int info = 0;  // the solver's return (0: solved)
};

// Siconos' TimeStepping with MoreauJeanOSI(theta, gamma) and an LCP solved by Lemke or by
// enumeration (SICONOS_LCP_LEMKE, SICONOS_LCP_ENUM), fixed step h.
class TimeStepper {
 public:
  TimeStepper(const ModelSpec& spec, double h, double theta, double gamma, bool enumeration);
  ~TimeStepper();
  TimeStepper(const TimeStepper&) = delete;
  TimeStepper& operator=(const TimeStepper&) = delete;

  // One step; false (and nothing done) when Siconos has no next step.
  bool step();
  // The bodies' displacements and velocities (one each per body).
  void state(double* u, double* v) const;
  // Contact j: in the index set of the coming step; its impulse in the last step.
  bool active(int j) const;
  double impulse(int j) const;
  const LcpCall& last_lcp() const;
  // What MoreauJeanOSI holds: theta, gamma, whether gamma is used, the activation threshold.
  double theta() const;
  double gamma() const;
  bool uses_gamma() const;
  double activation_threshold() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Siconos' EventDriven simulation with LsodarOSI (tolerances set by the array form of
// setTol, itol = 1) and Lemke for its impact and acceleration LCPs; the run stops at every
// multiple of output_step and at every root LSODAR finds.
class EventDrivenRun {
 public:
  EventDrivenRun(const ModelSpec& spec, double output_step, double rtol, double atol);
  ~EventDrivenRun();
  EventDrivenRun(const EventDrivenRun&) = delete;
  EventDrivenRun& operator=(const EventDrivenRun&) = delete;

  bool has_next() const;
  // Integrates to the next event; true if LSODAR stopped at a root. The state is then the
  // one before the event is processed (before an impact).
  bool advance();
  // Processes the event (impact LCP, acceleration LCP, index sets).
  void process();
  double time() const;  // of the last processed event
  void state(double* u, double* v) const;
  double impulse(int j) const;  // of the last processed event (0 at an output point)
  double force(int j) const;    // the contact force of the acceleration LCP
  bool closed(int j) const;     // in Siconos' index set 2: persistent contact
  // What LsodarOSI and EventDriven hold.
  long itol() const;
  double rtol() const;
  double atol() const;
  long itask() const;
  double event_tolerance() const;
  // LSODAR's steps and right-hand-side calls since this run was made.
  long lsodar_steps() const;
  long lsodar_rhs_calls() const;

 private:
  template <class F>
  void call(F&& f);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pb::siconos::engine
