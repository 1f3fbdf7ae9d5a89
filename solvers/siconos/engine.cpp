// Compiled as C++17 (engine.hpp says why); the only file that includes Siconos' headers.

#include "solvers/siconos/engine.hpp"
#include "solvers/siconos/buildings_engine.hpp"

#include <D1MinusLinearOSI.hpp>

#include <cstdint>
#include <EventDriven.hpp>
#include <Interaction.hpp>
#include <LCP.hpp>
#include <LagrangianLinearDiagonalDS.hpp>
#include <LagrangianLinearTIDS.hpp>
#include <LagrangianLinearTIR.hpp>
#include <LsodarOSI.hpp>
#include <MLCPProjectOnConstraints.hpp>
#include <MoreauJeanBilbaoOSI.hpp>
#include <MoreauJeanCombinedProjectionOSI.hpp>
#include <MoreauJeanDirectProjectionOSI.hpp>
#include <MoreauJeanOSI.hpp>
#include <NewMarkAlphaOSI.hpp>
#include <NewtonImpactNSL.hpp>
#include <NonSmoothDynamicalSystem.hpp>
#include <SchatzmanPaoliOSI.hpp>
#include <SiconosVector.hpp>
#include <SimpleMatrix.hpp>
#include <SolverOptions.h>
#include <TimeDiscretisation.hpp>
#include <TimeStepping.hpp>
#include <TimeSteppingCombinedProjection.hpp>
#include <TimeSteppingD1Minus.hpp>
#include <TimeSteppingDirectProjection.hpp>
#include <Topology.hpp>
#include <lcp_cst.h>
#include <mlcp_cst.h>

#include <cstdlib>
#include <iostream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace pb::siconos::engine {

namespace {

std::mutex& siconos_lock() {
  static std::mutex m;
  return m;
}
using Guard = std::lock_guard<std::mutex>;

// Siconos throws Siconos::exception, whose what() says only "std::exception": the message
// it carries is passed on in a std::runtime_error.
template <class F>
decltype(auto) translated(F&& f) {
  try {
    return f();
  } catch (const Siconos::exception& e) {
    const std::string* message = boost::get_error_info<Siconos::exception::extra_message>(e);
    throw std::runtime_error(message ? *message : boost::diagnostic_information(e));
  }
}

// std::cout's output while it lives, kept instead of printed: Siconos' event-driven code prints
// an interaction's state to std::cout before it throws. Swapping std::cout's buffer is safe
// only while no other thread writes to std::cout: poundbench writes its output after its
// sweeps, and a time-stepping run prints nothing (TimeStepper's LCP hook).
class CoutCapture {
 public:
  CoutCapture() : old_(std::cout.rdbuf(text_.rdbuf())) {}
  ~CoutCapture() { std::cout.rdbuf(old_); }
  CoutCapture(const CoutCapture&) = delete;
  CoutCapture& operator=(const CoutCapture&) = delete;
  // What Siconos printed before it threw, in one line: LSODAR's istate when it failed, or
  // else the last line (EventDriven's offending output).
  std::string gist() const {
    std::istringstream in(text_.str());
    std::string line, last;
    while (std::getline(in, line)) {
      if (line.find("Istate") != std::string::npos) return line;
      if (!line.empty()) last = line;
    }
    return last;
  }

 private:
  std::ostringstream text_;
  std::streambuf* old_;
};

// The parameters of a body's load plugin, in its DynamicalSystem's z vector.
// An address (a sampler's, a watch's) is held as two whole numbers below 2^32, each exact as
// a double.
enum LoadParameter {
  kMass,
  kCosine,
  kAmplitude,
  kSampleStep,
  kSamplerHigh,
  kSamplerLow,
  kWatchHigh,
  kWatchLow,
  kLoadParameters
};

// ModelSpec::stop, where the load plugin finds it.
struct Watch {
  bool (*stop)(void*);
  void* data;
};

void put_address(SiconosVector& z, int high, const void* p) {
  const auto address = reinterpret_cast<std::uintptr_t>(p);
  z(static_cast<unsigned>(high)) = static_cast<double>(address >> 32);
  z(static_cast<unsigned>(high + 1)) = static_cast<double>(address & 0xffffffffu);
}

template <class T>
T* address_in(const double* z, int high) {
  return reinterpret_cast<T*>((static_cast<std::uintptr_t>(z[high]) << 32) | static_cast<std::uintptr_t>(z[high + 1]));
}

// Siconos' external force F_ext(t) = -m a_g(t) of one body. A plain function of t and z:
// reentrant (a sampler and a watch are their run's own).
void ground_load(double t, unsigned int, double* f, unsigned int, double* z) {
  if (const Watch* watch = address_in<Watch>(z, kWatchHigh); watch && watch->stop(watch->data)) throw Stopped{};
  if (GroundSampler* sampler = address_in<GroundSampler>(z, kSamplerHigh)) {
    f[0] = -z[kMass] * (*sampler)(t);
    return;
  }
  f[0] = -z[kMass] * ground_sample(z[kCosine] != 0.0, z[kAmplitude], t, z[kSampleStep]);
}

SP::SimpleMatrix scalar_matrix(double x) {
  auto m = std::make_shared<SimpleMatrix>(1, 1);
  (*m)(0, 0) = x;
  return m;
}

SP::SiconosVector scalar_vector(double x) {
  auto v = std::make_shared<SiconosVector>(1);
  (*v)(0) = x;
  return v;
}

// One LagrangianLinearTIDS per body (a LagrangianLinearDiagonalDS, with the same diagonal
// M, K, C, where `diagonal`: MoreauJeanBilbaoOSI takes nothing else), one Interaction
// (LagrangianLinearTIR, NewtonImpactNSL) per contact. Call under siconos_lock().
struct Model {
  SP::NonSmoothDynamicalSystem nsds;
  std::vector<SP::LagrangianDS> bodies;
  std::vector<SP::Interaction> contacts;
  // The load plugin's sampler and watch, kept as long as the model: a run's ModelSpec may be
  // a temporary.
  std::shared_ptr<GroundSampler> sampler;
  std::unique_ptr<Watch> watch;
};

Model make_model(const ModelSpec& spec, bool diagonal = false) {
  Model m;
  m.sampler = spec.sampler;
  if (spec.stop) m.watch = std::make_unique<Watch>(Watch{spec.stop, spec.stop_data});
  m.nsds = std::make_shared<NonSmoothDynamicalSystem>(0.0, spec.t_end);
  for (const BodySpec& b : spec.bodies) {
    SP::LagrangianDS body;
    if (diagonal)
      body = std::make_shared<LagrangianLinearDiagonalDS>(scalar_vector(b.u0), scalar_vector(b.v0), scalar_vector(b.k),
                                                          scalar_vector(b.c), scalar_vector(b.m));
    else
      body = std::make_shared<LagrangianLinearTIDS>(scalar_vector(b.u0), scalar_vector(b.v0), scalar_matrix(b.m),
                                                    scalar_matrix(b.k), scalar_matrix(b.c));
    auto z = std::make_shared<SiconosVector>(kLoadParameters);
    (*z)(kMass) = b.m;
    (*z)(kCosine) = spec.cosine ? 1.0 : 0.0;
    (*z)(kAmplitude) = spec.amplitude;
    (*z)(kSampleStep) = spec.sample_step;
    put_address(*z, kSamplerHigh, spec.sampler.get());
    put_address(*z, kWatchHigh, m.watch.get());
    body->setzPtr(z);
    body->setComputeFExtFunction(&ground_load);
    m.nsds->insertDynamicalSystem(body);
    m.bodies.push_back(body);
  }
  for (const ContactSpec& c : spec.contacts) {
    // y = C q + delta over (left, right), or over the right body alone against the wall.
    const bool wall = c.left < 0;
    auto matrix = std::make_shared<SimpleMatrix>(1, wall ? 1 : 2);
    (*matrix)(0, 0) = wall ? 1.0 : -1.0;
    if (!wall) (*matrix)(0, 1) = 1.0;
    auto relation = std::make_shared<LagrangianLinearTIR>(matrix, scalar_vector(spec.delta));
    auto contact = std::make_shared<Interaction>(std::make_shared<NewtonImpactNSL>(spec.eps), relation);
    const auto& right = m.bodies[static_cast<std::size_t>(c.right)];
    if (wall)
      m.nsds->link(contact, right);
    else
      m.nsds->link(contact, m.bodies[static_cast<std::size_t>(c.left)], right);
    m.contacts.push_back(contact);
  }
  return m;
}

void read_state(const Model& m, double* u, double* v) {
  for (std::size_t i = 0; i < m.bodies.size(); ++i) {
    u[i] = m.bodies[i]->q()->getValue(0);
    v[i] = m.bodies[i]->velocity()->getValue(0);
  }
}

// Contact j's multiplier at a level: 1 the impulse of an impact, 2 the force of a closed contact.
double multiplier(const Model& m, int j, unsigned int level) {
  return m.contacts[static_cast<std::size_t>(j)]->lambda(level)->getValue(0);
}

// Siconos' objects hold each other in cycles of shared pointers: a simulation's integrators
// and one-step problems hold it, it holds the model, and the model's graph of dynamical
// systems holds the integrators, which hold the graph. Left alone, the objects of a run are
// never freed (valgrind: 20 KB a run, 16 KB a point through a sweep). Cut every cycle.
void cut_cycles(const SP::Simulation& sim) {
  if (!sim) return;
  for (const SP::OneStepIntegrator& osi : *sim->oneStepIntegrators()) osi->setSimulationPtr(SP::Simulation());
  for (const SP::OneStepNSProblem& problem : *sim->oneStepNSProblems())
    if (problem) problem->setSimulationPtr(SP::Simulation());
  DynamicalSystemsGraph& bodies = *sim->nonSmoothDynamicalSystem()->topology()->dSG(0);
  DynamicalSystemsGraph::VIterator v, end;
  for (std::tie(v, end) = bodies.vertices(); v != end; ++v) bodies.properties(*v).osi.reset();
}

// An LCP with its solver's options. LCP(int) makes them and never frees the struct itself
// (Siconos 4.4's solver_options_delete frees only what it points to): 120 bytes a problem.
SP::LCP make_lcp(int solver) {
  return std::make_shared<LCP>(SP::SolverOptions(solver_options_create(solver), [](SolverOptions* options) {
    solver_options_delete(options);
    std::free(options);
  }));
}

// The projections' MLCP. Siconos 4.4's MLCP::solve calls mlcp_driver_init before every solve,
// and for enumeration it callocs the options' iWork and dWork anew without freeing the last
// ones (a static function of libsiconos_numerics; found by LeakSanitizer: ~20 bytes a solve,
// 1288 blocks over the contract's 40 combined-projection runs). The arrays of the last solve
// are dead by the next one: this frees them first.
class ProjectionMlcp : public MLCPProjectOnConstraints {
 public:
  using MLCPProjectOnConstraints::MLCPProjectOnConstraints;
  int compute(double time) override {
    SolverOptions& o = *numericsSolverOptions();
    std::free(o.iWork);
    std::free(o.dWork);
    o.iWork = nullptr;
    o.dWork = nullptr;
    o.iWorkSize = o.dWorkSize = 0;
    return MLCPProjectOnConstraints::compute(time);
  }
};

bool in_index_set(const Model& m, unsigned int level, int j) {
  return m.nsds->topology()->indexSet(level)->is_vertex(m.contacts[static_cast<std::size_t>(j)]);
}

// TimeStepping hands each LCP's info to a process-wide hook; its default prints a warning to
// stdout and carries on. This one, set once, keeps it for the calling thread instead.
thread_local int t_lcp_info = 0;
void keep_lcp_info(int info, Simulation*) { t_lcp_info = info; }

}  // namespace

// ---- TimeStepper ----

struct TimeStepper::Impl {
  Model model;
  StepperOptions options;
  double h = 0.0;
  SP::OneStepIntegrator osi;
  SP::MoreauJeanOSI moreau_jean;  // for the moreau_jean integrator's test hooks
  SP::LCP lcp;                    // the velocity (impact; position for Schatzman-Paoli) LCP
  SP::LCP force_lcp;              // D1MinusLinear's
  SP::Simulation sim;
  SP::TimeStepping time_stepping;  // sim, unless D1MinusLinear's TimeSteppingD1Minus
  SP::TimeSteppingCombinedProjection combined;
  SP::TimeSteppingDirectProjection direct;
  int level = 1;                 // the index set of lcp; -1: none (every contact)
  int counter = 0;               // the iparam entry only a solver call writes (see step())
  std::vector<double> impulses;  // of the last step, read before Siconos zeroes them
  LcpCall last;
  long projections = 0;
  double violation = 0.0;
  void build(const ModelSpec& spec);
  ~Impl() { cut_cycles(sim); }
};

// The simulation of `options` around `model`, not yet initialised. Call under siconos_lock().
void TimeStepper::Impl::build(const ModelSpec& spec) {
  Impl& s = *this;
  const StepperOptions& o = s.options;
  const int lcp_solver = o.enumeration ? SICONOS_LCP_ENUM : SICONOS_LCP_LEMKE;
  const auto td = std::make_shared<TimeDiscretisation>(0.0, s.h);
  s.model = make_model(spec, o.integrator == Integrator::bilbao);
  s.lcp = make_lcp(lcp_solver);
  // The projections' MLCP by enumeration, as Siconos' own examples of both schemes set it:
  // of Siconos 4.4's MLCP solvers, PGS refuses this storage (printing "Wrong Storage") and
  // SICONOS_MLCP_LCP_LEMKE aborts (lcp_lexicolemke: assertion dim > 0). Enumeration tries up to
  // 2^n active sets: siconos_solver.cpp keeps it to kMaxEnumerationContacts contacts.
  const int mlcp_solver = SICONOS_MLCP_ENUM;
  // A projecting scheme's simulation (combined or direct) on s.osi, with its MLCP projection
  // and the run's projection iterations and tolerance.
  const auto projecting = [&](auto& stepping) {
    using Stepping = typename std::decay_t<decltype(stepping)>::element_type;
    auto mlcp = SP::SolverOptions(solver_options_create(mlcp_solver), [](SolverOptions* p) {
      solver_options_delete(p);
      std::free(p);
    });
    stepping = std::make_shared<Stepping>(s.model.nsds, td, s.osi, s.lcp, std::make_shared<ProjectionMlcp>(mlcp));
    stepping->setProjectionMaxIteration(static_cast<unsigned int>(o.projection_iterations));
    stepping->setConstraintTolUnilateral(o.projection_tol);
    stepping->setConstraintTol(o.projection_tol);
    s.sim = stepping;
  };
  switch (o.integrator) {
    case Integrator::moreau_jean:
      s.moreau_jean = std::make_shared<MoreauJeanOSI>(o.theta, o.gamma);
      s.osi = s.moreau_jean;
      s.sim = std::make_shared<TimeStepping>(s.model.nsds, td, s.osi, s.lcp);
      break;
    case Integrator::schatzman_paoli:
      s.osi = std::make_shared<SchatzmanPaoliOSI>(o.theta);
      s.sim = std::make_shared<TimeStepping>(s.model.nsds, td, s.osi, s.lcp);
      s.level = -1;
      break;
    case Integrator::d1_minus_linear: {
      s.level = -1;
      s.osi = std::make_shared<D1MinusLinearOSI>();
      s.force_lcp = make_lcp(lcp_solver);
      auto d1 = std::make_shared<TimeSteppingD1Minus>(s.model.nsds, td, 2);
      d1->insertIntegrator(s.osi);
      d1->insertNonSmoothProblem(s.lcp, SICONOS_OSNSP_TS_VELOCITY);
      d1->insertNonSmoothProblem(s.force_lcp, SICONOS_OSNSP_TS_VELOCITY + 1);
      s.sim = d1;
      break;
    }
    case Integrator::combined_projection: {
      s.level = -1;
      s.osi = std::make_shared<MoreauJeanCombinedProjectionOSI>(o.theta);
      projecting(s.combined);
      break;
    }
    case Integrator::direct_projection: {
      s.osi = std::make_shared<MoreauJeanDirectProjectionOSI>(o.theta, o.gamma);
      projecting(s.direct);
      break;
    }
    case Integrator::bilbao:
      s.osi = std::make_shared<MoreauJeanBilbaoOSI>();
      s.sim = std::make_shared<TimeStepping>(s.model.nsds, td, s.osi, s.lcp);
      break;
  }
}

TimeStepper::TimeStepper(const ModelSpec& spec, double h, const StepperOptions& options) {
  const Guard guard(siconos_lock());
  try {
    translated([&] {
      impl_ = std::make_unique<Impl>();
      impl_->options = options;
      impl_->h = h;
      impl_->build(spec);
      impl_->time_stepping = std::dynamic_pointer_cast<TimeStepping>(impl_->sim);
      if (impl_->time_stepping) {
        static std::once_flag hook;
        std::call_once(hook, [&] { impl_->time_stepping->setCheckSolverFunction(&keep_lcp_info); });
      }
      impl_->sim->initialize();
      // Lemke writes its pivot count, enumeration the number of the case it is at; the
      // driver's shortcuts write neither.
      impl_->counter = options.enumeration ? static_cast<int>(SICONOS_LCP_IPARAM_ENUM_CURRENT_ENUM)
                                           : static_cast<int>(SICONOS_IPARAM_ITER_DONE);
      if (impl_->counter >= impl_->lcp->numericsSolverOptions()->iSize)
        throw std::runtime_error("the LCP solver's options have no iparam entry " + std::to_string(impl_->counter));
      impl_->impulses.assign(spec.contacts.size(), 0.0);
    });
  } catch (...) {
    impl_.reset();  // under the lock, as every Siconos object is unmade
    throw;
  }
}

TimeStepper::~TimeStepper() {
  const Guard guard(siconos_lock());
  impl_.reset();
}

bool TimeStepper::step() {
  Impl& s = *impl_;
  if (!s.sim->hasNextEvent()) return false;
  const auto nc = s.model.contacts.size();
  int active = 0;
  if (s.level >= 0)
    for (std::size_t j = 0; j < nc; ++j) active += in_index_set(s.model, 1, static_cast<int>(j)) ? 1 : 0;
  SolverOptions& options = *s.lcp->numericsSolverOptions();
  options.iparam[s.counter] = -1;
  t_lcp_info = 0;
  translated([&] {
    if (s.time_stepping)
      s.time_stepping->computeOneStep();
    else
      s.sim->advanceToEvent();
  });
  s.last = LcpCall{};
  s.last.info = t_lcp_info;
  if (active > 0 && s.options.integrator == Integrator::moreau_jean) {
    const SiconosVector& q = *s.lcp->q();
    s.last.called = true;
    s.last.rows = static_cast<int>(q.size());
    s.last.q_nonnegative = true;
    for (unsigned int i = 0; i < q.size(); ++i) s.last.q_nonnegative = s.last.q_nonnegative && q.getValue(i) >= 0.0;
    s.last.counter_written = options.iparam[s.counter] != -1;
  }
  // Before nextStep(): it zeroes the impulse of a contact that leaves the index set.
  for (std::size_t j = 0; j < nc; ++j) {
    const Interaction& c = *s.model.contacts[j];
    switch (s.options.integrator) {
      case Integrator::schatzman_paoli: s.impulses[j] = c.lambda(0)->getValue(0) / s.h; break;
      case Integrator::d1_minus_linear:
        s.impulses[j] = c.lambda(1)->getValue(0) + s.h * c.lambda(2)->getValue(0);
        break;
      default: s.impulses[j] = c.lambda(1)->getValue(0); break;
    }
  }
  if (s.combined) {
    s.projections += s.combined->nbCumulatedProjectionIteration();
    s.violation = std::max(s.violation, s.combined->maxViolationUnilateral());
  } else if (s.direct) {
    s.projections += s.direct->nbProjectionIteration();
    s.violation = std::max(s.violation, s.direct->maxViolationUnilateral());
  }
  translated([&] {
    if (s.time_stepping)
      s.time_stepping->nextStep();
    else
      s.sim->processEvents();
  });
  return true;
}

void TimeStepper::state(double* u, double* v) const { read_state(impl_->model, u, v); }
bool TimeStepper::active(int j) const { return impl_->level >= 0 && in_index_set(impl_->model, 1, j); }
bool TimeStepper::has_index_set() const { return impl_->level >= 0; }
double TimeStepper::impulse(int j) const { return impl_->impulses[static_cast<std::size_t>(j)]; }
const LcpCall& TimeStepper::last_lcp() const { return impl_->last; }
long TimeStepper::projection_iterations() const { return impl_->projections; }
double TimeStepper::max_violation() const { return impl_->violation; }
double TimeStepper::theta() const { return impl_->moreau_jean ? impl_->moreau_jean->theta() : impl_->options.theta; }
double TimeStepper::gamma() const { return impl_->moreau_jean ? impl_->moreau_jean->gamma() : impl_->options.gamma; }
bool TimeStepper::uses_gamma() const { return impl_->moreau_jean && impl_->moreau_jean->useGamma(); }
double TimeStepper::activation_threshold() const {
  return impl_->moreau_jean ? impl_->moreau_jean->constraintActivationThreshold() : 0.0;
}

// ---- EventDrivenRun ----

struct EventDrivenRun::Impl {
  Guard guard{siconos_lock()};  // first member: held until the last Siconos object is gone
  CoutCapture printed;
  Model model;
  SP::LsodarOSI osi;
  SP::EventDriven sim;
  int steps0 = 0, rhs0 = 0;  // LsodarOSI's process-wide counters when the run was made
  ~Impl() { cut_cycles(sim); }
};

// A Siconos call: its exception as a std::runtime_error with its message and the gist of what
// Siconos printed before it threw.
template <class F>
void EventDrivenRun::call(F&& f) {
  try {
    translated(f);
  } catch (const std::exception& e) {
    const std::string printed = impl_->printed.gist();
    throw std::runtime_error(std::string(e.what()) + (printed.empty() ? "" : " (" + printed + ")"));
  }
}

EventDrivenRun::EventDrivenRun(const ModelSpec& spec, double output_step, double rtol, double atol)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  call([&] {
    s.model = make_model(spec);
    s.osi = std::make_shared<LsodarOSI>();
    s.sim = std::make_shared<EventDriven>(s.model.nsds, std::make_shared<TimeDiscretisation>(0.0, output_step));
    s.sim->insertIntegrator(s.osi);
    s.sim->insertNonSmoothProblem(make_lcp(SICONOS_LCP_LEMKE), SICONOS_OSNSP_ED_IMPACT);
    s.sim->insertNonSmoothProblem(make_lcp(SICONOS_LCP_LEMKE), SICONOS_OSNSP_ED_SMOOTH_ACC);
    // The array form: the scalar setTol(itol, rtol, atol) of Siconos 4.4 stores rtol as atol.
    SA::doublereal r(new doublereal[1]), a(new doublereal[1]);
    r[0] = rtol;
    a[0] = atol;
    s.osi->setTol(1, r, a);
    s.sim->initialize();
  });
  s.steps0 = LsodarOSI::count_steps();
  s.rhs0 = LsodarOSI::count_rhs_call();
}

EventDrivenRun::~EventDrivenRun() = default;

bool EventDrivenRun::has_next() const { return impl_->sim->hasNextEvent(); }
bool EventDrivenRun::advance() {
  call([&] { impl_->sim->advanceToEvent(); });
  return impl_->sim->istate() == 3;  // LSODAR's istate: 3, it returned at a root of g
}
void EventDrivenRun::process() {
  call([&] { impl_->sim->processEvents(); });
}

double EventDrivenRun::time() const { return impl_->sim->startingTime(); }
void EventDrivenRun::state(double* u, double* v) const { read_state(impl_->model, u, v); }
double EventDrivenRun::impulse(int j) const { return multiplier(impl_->model, j, 1); }
double EventDrivenRun::force(int j) const { return multiplier(impl_->model, j, 2); }
bool EventDrivenRun::closed(int j) const { return in_index_set(impl_->model, 2, j); }
long EventDrivenRun::itol() const { return static_cast<long>(impl_->osi->intData(2)); }
double EventDrivenRun::rtol() const { return impl_->osi->getRtol()[0]; }
double EventDrivenRun::atol() const { return impl_->osi->getAtol()[0]; }
long EventDrivenRun::itask() const { return static_cast<long>(impl_->osi->intData(3)); }
double EventDrivenRun::event_tolerance() const { return impl_->sim->toleranceED(); }
long EventDrivenRun::lsodar_steps() const { return LsodarOSI::count_steps() - impl_->steps0; }
long EventDrivenRun::lsodar_rhs_calls() const { return LsodarOSI::count_rhs_call() - impl_->rhs0; }

// ---- NewmarkAlphaRun ----

namespace {

// NewMarkAlphaOSI with a count of its Newton iterations: EventDriven::newtonSolve calls
// prepareNewtonIteration once per iteration, and has no other exit than convergence.
class WatchedNewMarkAlpha : public NewMarkAlphaOSI {
 public:
  WatchedNewMarkAlpha(double rho_infty, bool (*stop)(void*), void* stop_data)
      : NewMarkAlphaOSI(rho_infty, false), stop_(stop), stop_data_(stop_data) {}

  void prepareNewtonIteration(double time) override {
    ++in_advance_;
    ++total_;
    const bool stopped = stop_ && stop_(stop_data_);
    if (in_advance_ > limit_ || stopped) {
      NewmarkAlphaRun::NewtonLoop loop;
      loop.iterations = in_advance_ - 1;
      loop.k_sign_flips = flips_;
      loop.stopped = stopped;
      throw loop;
    }
    // Whether this call changes the sign of the first body's stiffness (computeW negating
    // a LagrangianLinearTIDS's K in place): read before and after.
    const double before = first_k();
    NewMarkAlphaOSI::prepareNewtonIteration(time);
    if ((before > 0.0) != (first_k() > 0.0)) ++flips_;
  }

  void new_advance() { in_advance_ = flips_ = 0; }
  void set_limit(long limit) { limit_ = limit; }
  long total() const { return total_; }
  void watch(SP::LagrangianLinearTIDS body) { first_ = std::move(body); }

 private:
  double first_k() const { return first_ && first_->K() ? first_->K()->getValue(0, 0) : 0.0; }

  long limit_ = 0;
  bool (*stop_)(void*);
  void* stop_data_;
  long in_advance_ = 0, total_ = 0, flips_ = 0;
  SP::LagrangianLinearTIDS first_;
};

}  // namespace

struct NewmarkAlphaRun::Impl {
  Guard guard{siconos_lock()};  // first member: held until the last Siconos object is gone
  CoutCapture printed;           // EventDriven::newtonSolve's warnings
  Model model;
  std::vector<BodySpec> made;  // the bodies' K and C as made
  std::shared_ptr<WatchedNewMarkAlpha> osi;
  SP::EventDriven sim;
  ~Impl() { cut_cycles(sim); }
};

NewmarkAlphaRun::NewmarkAlphaRun(const ModelSpec& spec, double h, double rho_infty, long overrun,
                                 bool (*stop)(void*), void* stop_data)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  translated([&] {
    s.model = make_model(spec);
    s.made = spec.bodies;
    s.osi = std::make_shared<WatchedNewMarkAlpha>(rho_infty, stop, stop_data);
    s.osi->watch(std::dynamic_pointer_cast<LagrangianLinearTIDS>(s.model.bodies.front()));
    s.sim = std::make_shared<EventDriven>(s.model.nsds, std::make_shared<TimeDiscretisation>(0.0, h));
    s.sim->insertIntegrator(s.osi);
    s.sim->insertNonSmoothProblem(make_lcp(SICONOS_LCP_LEMKE), SICONOS_OSNSP_ED_IMPACT);
    s.sim->insertNonSmoothProblem(make_lcp(SICONOS_LCP_LEMKE), SICONOS_OSNSP_ED_SMOOTH_ACC);
    s.sim->insertNonSmoothProblem(make_lcp(SICONOS_LCP_LEMKE), SICONOS_OSNSP_ED_SMOOTH_POS);
    s.osi->set_limit(overrun * static_cast<long>(s.sim->newtonMaxIteration()));
    s.sim->initialize();
  });
}

NewmarkAlphaRun::~NewmarkAlphaRun() = default;

bool NewmarkAlphaRun::has_next() const { return impl_->sim->hasNextEvent(); }

void NewmarkAlphaRun::advance() {
  Impl& s = *impl_;
  s.osi->new_advance();
  try {
    translated([&] {
      s.sim->advanceToEvent();
      s.sim->processEvents();
    });
  } catch (NewtonLoop& loop) {
    loop.siconos_limit = static_cast<long>(s.sim->newtonMaxIteration());
    loop.time = s.sim->startingTime();
    throw;
  }
}

double NewmarkAlphaRun::time() const { return impl_->sim->startingTime(); }
void NewmarkAlphaRun::state(double* u, double* v) const { read_state(impl_->model, u, v); }
double NewmarkAlphaRun::impulse(int j) const { return multiplier(impl_->model, j, 1); }
double NewmarkAlphaRun::force(int j) const { return multiplier(impl_->model, j, 2); }
long NewmarkAlphaRun::newton_iterations() const { return impl_->osi->total(); }
int NewmarkAlphaRun::changed_body(double& k, double& c) const {
  const Impl& s = *impl_;
  for (std::size_t i = 0; i < s.model.bodies.size(); ++i) {
    const auto& body = static_cast<const LagrangianLinearTIDS&>(*s.model.bodies[i]);
    k = body.K() ? body.K()->getValue(0, 0) : 0.0;
    c = body.C() ? body.C()->getValue(0, 0) : 0.0;
    if (k != s.made[i].k || c != s.made[i].c) return static_cast<int>(i);
  }
  return -1;
}

// ---- BuildingsStepper ----

namespace {

// The buildings' load plugin: F_ext = -M 1 a_g(t) of one building, its sampler's address in
// z[0], z[1] and its floor masses after them.
void floors_load(double t, unsigned int n, double* f, unsigned int, double* z) {
  GroundSampler& sampler = *address_in<GroundSampler>(z, 0);
  const double a = sampler(t);
  for (unsigned int i = 0; i < n; ++i) f[i] = -z[2 + i] * a;
}

SP::SimpleMatrix square(int n, const std::vector<double>& rows) {
  auto m = std::make_shared<SimpleMatrix>(static_cast<unsigned>(n), static_cast<unsigned>(n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      (*m)(static_cast<unsigned>(i), static_cast<unsigned>(j)) = rows[static_cast<std::size_t>(i * n + j)];
  return m;
}

}  // namespace

struct BuildingsStepper::Impl {
  std::shared_ptr<GroundSampler> sampler;  // kept as long as the bodies that point to it
  SP::NonSmoothDynamicalSystem nsds;
  std::vector<SP::LagrangianLinearTIDS> bodies;
  std::vector<SP::Interaction> contacts;
  SP::LCP lcp;
  SP::TimeStepping sim;
  int info = 0;
  ~Impl() { cut_cycles(sim); }
};

BuildingsStepper::BuildingsStepper(const BuildingsSpec& spec, double h, double theta, double gamma, bool enumeration) {
  const Guard guard(siconos_lock());
  try {
    translated([&] {
      impl_ = std::make_unique<Impl>();
      Impl& s = *impl_;
      s.sampler = spec.sampler;
      s.nsds = std::make_shared<NonSmoothDynamicalSystem>(0.0, spec.t_end);
      for (const BuildingSpec& b : spec.buildings) {
        const auto n = static_cast<unsigned>(b.floors);
        auto mass = std::make_shared<SimpleMatrix>(n, n);  // zeroed
        auto z = std::make_shared<SiconosVector>(2 + n);
        put_address(*z, 0, spec.sampler.get());
        for (unsigned i = 0; i < n; ++i) {
          (*mass)(i, i) = b.m[i];
          (*z)(2 + i) = b.m[i];
        }
        auto body = std::make_shared<LagrangianLinearTIDS>(std::make_shared<SiconosVector>(n),
                                                           std::make_shared<SiconosVector>(n), mass,
                                                           square(b.floors, b.k), square(b.floors, b.c));
        body->setzPtr(z);
        body->setComputeFExtFunction(&floors_load);
        s.nsds->insertDynamicalSystem(body);
        s.bodies.push_back(body);
      }
      for (const FloorPairSpec& c : spec.contacts) {
        // y = C (q_left, q_right) + delta: -1 at the left building's floor, +1 at the right's.
        const int nl = spec.buildings[static_cast<std::size_t>(c.left)].floors;
        const int nr = spec.buildings[static_cast<std::size_t>(c.right)].floors;
        auto matrix = std::make_shared<SimpleMatrix>(1, static_cast<unsigned>(nl + nr));  // zeroed
        (*matrix)(0, static_cast<unsigned>(c.left_floor)) = -1.0;
        (*matrix)(0, static_cast<unsigned>(nl + c.right_floor)) = 1.0;
        auto relation = std::make_shared<LagrangianLinearTIR>(matrix, scalar_vector(spec.delta));
        auto contact = std::make_shared<Interaction>(std::make_shared<NewtonImpactNSL>(spec.eps), relation);
        s.nsds->link(contact, s.bodies[static_cast<std::size_t>(c.left)], s.bodies[static_cast<std::size_t>(c.right)]);
        s.contacts.push_back(contact);
      }
      s.lcp = make_lcp(enumeration ? SICONOS_LCP_ENUM : SICONOS_LCP_LEMKE);
      s.sim = std::make_shared<TimeStepping>(s.nsds, std::make_shared<TimeDiscretisation>(0.0, h),
                                             std::make_shared<MoreauJeanOSI>(theta, gamma), s.lcp);
      s.sim->setCheckSolverFunction(&keep_lcp_info);
      s.sim->initialize();
    });
  } catch (...) {
    impl_.reset();  // under the lock, as every Siconos object is unmade
    throw;
  }
}

BuildingsStepper::~BuildingsStepper() {
  const Guard guard(siconos_lock());
  impl_.reset();
}

bool BuildingsStepper::step() {
  Impl& s = *impl_;
  if (!s.sim->hasNextEvent()) return false;
  t_lcp_info = 0;
  translated([&] {
    s.sim->computeOneStep();
    s.sim->nextStep();
  });
  s.info = t_lcp_info;
  return true;
}

void BuildingsStepper::state(double* u, double* v) const {
  std::size_t at = 0;
  for (const auto& body : impl_->bodies) {
    const SiconosVector &q = *body->q(), &w = *body->velocity();
    for (unsigned i = 0; i < q.size(); ++i, ++at) {
      u[at] = q.getValue(i);
      v[at] = w.getValue(i);
    }
  }
}

bool BuildingsStepper::active(int j) const {
  return impl_->nsds->topology()->indexSet(1)->is_vertex(impl_->contacts[static_cast<std::size_t>(j)]);
}

int BuildingsStepper::lcp_info() const { return impl_->info; }

}  // namespace pb::siconos::engine
