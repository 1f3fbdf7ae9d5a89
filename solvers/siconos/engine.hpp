#pragma once
// The one place that touches Siconos: a run's model and simulation behind three small
// classes, one per kind of integration, each hiding its Siconos objects (engine.cpp). The
// step loops, the counts and the Result are the callers' (time_stepping.cpp,
// event_driven.cpp, newmark_alpha.cpp).
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
// lock and steps without it; an EventDrivenRun and a NewmarkAlphaRun hold the lock from
// construction to destruction (README, thread safety).

#include <memory>
#include <vector>

namespace pb::siconos::engine {

struct BodySpec {
  double m, k, c;  // mass, stiffness, damping
  double u0, v0;   // start state
};

// A ground load other than the paper's pulses (a record, a pulse model): a_g at time t, both
// in the pulse's units, from the caller's side (model.cpp: through the one load interface,
// cases/load.hpp). One per run: it remembers where it last looked.
class GroundSampler {
 public:
  virtual ~GroundSampler() = default;
  virtual double operator()(double t) = 0;
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
  // Set: the load is the sampler's (cosine and amplitude are not used). The load plugin
  // reaches it through the body's z vector (engine.cpp).
  std::shared_ptr<GroundSampler> sampler;
  double t_end = 0.0;
  // Called at every evaluation of the load: once per body in Siconos' set-up and in every
  // right-hand side its integrator evaluates. True abandons the run: Stopped is thrown from
  // the load plugin, out of whatever Siconos (or LSODAR's Fortran) was doing, and the run
  // can only be destroyed. Null: never.
  bool (*stop)(void*) = nullptr;
  void* stop_data = nullptr;
};

// Thrown out of a run's construction and calls when ModelSpec::stop says so.
struct Stopped {};

// a_g in the pulse's units, sampled as Pulse::sample(t, step) does (defined with Pulse, in
// model.cpp): what the load plugin gives Siconos.
double ground_sample(bool cosine, double amplitude, double t, double step);

// The one-step integrators of Siconos' time-stepping simulations that a TimeStepper runs, each
// with the simulation class Siconos pairs it with:
//   moreau_jean          MoreauJeanOSI(theta, gamma) + TimeStepping, velocity-level LCP
//   schatzman_paoli      SchatzmanPaoliOSI(theta) + TimeStepping, position-level LCP on every
//                        contact (index set 0)
//   d1_minus_linear      D1MinusLinearOSI (half-explicit, acceleration level) +
//                        TimeSteppingD1Minus, an impact LCP and a force LCP
//   combined_projection  MoreauJeanCombinedProjectionOSI(theta) + TimeSteppingCombinedProjection,
//                        the velocity LCP then a position projection (MLCPProjectOnConstraints)
//   direct_projection    MoreauJeanDirectProjectionOSI(theta, gamma) + TimeSteppingDirectProjection
//   bilbao               MoreauJeanBilbaoOSI + TimeStepping, bodies as LagrangianLinearDiagonalDS
enum class Integrator { moreau_jean, schatzman_paoli, d1_minus_linear, combined_projection, direct_projection, bilbao };

struct StepperOptions {
  Integrator integrator = Integrator::moreau_jean;
  double theta = 0.5, gamma = 0.5;
  bool enumeration = false;        // every LCP by enumeration (SICONOS_LCP_ENUM), else Lemke
  double projection_tol = 1e-10;   // projections: the tolerance on a violated gap, pulse units
  int projection_iterations = 0;   // projections: most projection iterations per step
};

// What the dense LCP driver met on a step: its q's sign and size, and whether the solver's
// iteration counter was written (only a call of Lemke or enumeration writes it).
struct LcpCall {
  bool called = false;       // a contact was active: the driver ran
  bool q_nonnegative = false;
  int rows = 0;
  bool counter_written = false;
  int info = 0;  // the solver's return (0: solved)
};

// A Siconos time-stepping simulation with one of the integrators above, fixed step h.
class TimeStepper {
 public:
  TimeStepper(const ModelSpec& spec, double h, const StepperOptions& options);
  ~TimeStepper();
  TimeStepper(const TimeStepper&) = delete;
  TimeStepper& operator=(const TimeStepper&) = delete;

  // One step; false (and nothing done) when Siconos has no next step.
  bool step();
  // The bodies' displacements and velocities (one each per body).
  void state(double* u, double* v) const;
  // Contact j: in the index set that the coming step's velocity (or impact) LCP is built on
  // (always false for Schatzman-Paoli, whose LCP takes every contact); its impulse in the
  // last step: lambda(1) of the velocity-level schemes, lambda(1) + h lambda(2) of
  // D1MinusLinear (impact and force), lambda(0) / h of Schatzman-Paoli's position-level LCP.
  bool active(int j) const;
  double impulse(int j) const;
  // Whether active() follows an index set (false: Schatzman-Paoli).
  bool has_index_set() const;
  const LcpCall& last_lcp() const;
  // The projections' work so far: projection iterations summed over the steps, and the
  // largest violation of a gap left after a step's projection (pulse units).
  long projection_iterations() const;
  double max_violation() const;
  // What MoreauJeanOSI holds: theta, gamma, whether gamma is used, the activation threshold.
  double theta() const;
  double gamma() const;
  bool uses_gamma() const;
  double activation_threshold() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Siconos' EventDriven simulation with NewMarkAlphaOSI(rho_infty) (the nonsmooth
// generalized-alpha scheme of Chen, Acary, Virlez and Bruls), its three LCPs by Lemke, time
// step h. Siconos' EventDriven::newtonSolve has no way out but convergence (past its
// iteration limit it prints a warning and goes on); this run counts the scheme's Newton
// iterations itself (NewMarkAlphaOSI::prepareNewtonIteration, one call per iteration) and
// throws NewtonLoop once an advance has made `overrun` times EventDriven's own limit of them,
// or when `stop` (called once per iteration) says so.
class NewmarkAlphaRun {
 public:
  struct NewtonLoop {
    long iterations = 0;      // in the advance that was stopped
    long siconos_limit = 0;   // EventDriven's own newtonMaxIteration
    long k_sign_flips = 0;    // calls after which the first body's K had changed sign
    double time = 0.0;        // the advance's start (pulse units)
    bool stopped = false;     // ended by `stop`, not by the iteration limit
  };
  NewmarkAlphaRun(const ModelSpec& spec, double h, double rho_infty, long overrun, bool (*stop)(void*), void* stop_data);
  ~NewmarkAlphaRun();
  NewmarkAlphaRun(const NewmarkAlphaRun&) = delete;
  NewmarkAlphaRun& operator=(const NewmarkAlphaRun&) = delete;

  bool has_next() const;
  // To the next event and through it; throws NewtonLoop (see above), or std::runtime_error
  // with Siconos' message.
  void advance();
  double time() const;
  void state(double* u, double* v) const;
  double impulse(int j) const;
  double force(int j) const;
  long newton_iterations() const;  // over the run
  // The first body whose LagrangianLinearTIDS no longer holds the K and C it was made with
  // (-1: none), and what it holds now.
  int changed_body(double& k, double& c) const;

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
