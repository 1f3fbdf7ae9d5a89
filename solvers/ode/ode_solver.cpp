#include "solvers/ode/ode_solver.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "solvers/monitor.hpp"
#include "solvers/ode/world.hpp"

namespace pb::ode {

namespace {

// "steps=N" or "wh=X": what fixed the step (solvers/solver.hpp, time_step).
std::string step_setting(const Settings& s) {
  std::ostringstream out;
  if (s.wh > 0.0)
    out << "wh=" << s.wh;
  else
    out << "steps=" << (s.steps == 0 ? kDefaultSteps : s.steps);
  return out.str();
}

// The first step count whose end reaches t_end, to within 1e-9 of a step (as moreau_jean).
long step_count(double t_end, double h) { return static_cast<long>(std::ceil(t_end / h - 1e-9)); }

std::string check_config(const Config& c) {
  if (c.stepper == Stepper::quickstep && c.iterations < 1) return "iterations: must be >= 1";
  if (c.stepper == Stepper::quickstep && !(c.sor > 0.0 && c.sor < 2.0)) return "sor: must be in (0, 2)";
  if (!(c.erp >= 0.0 && c.erp <= 1.0)) return "erp: must be in [0, 1]";
  if (!(c.cfm >= 0.0)) return "cfm: must be >= 0";
  if (!(c.bounce_vel >= 0.0)) return "bounce_vel: must be >= 0";
  if (!(c.surface_layer >= 0.0)) return "surface_layer: must be >= 0";
  if (!(c.max_vel >= 0.0)) return "max_vel: must be >= 0";
  return {};
}

// The state a step starts from and what it needs to remember of the step before.
struct State {
  std::vector<double> u, v;        // per body, read back from ODE after each step
  std::vector<double> g, rate;     // per contact: gap and gap rate
  std::vector<double> lambda;      // per contact: force of the last step (0 if no joint)
  std::vector<char> joint;     // a contact joint was made for the last step
  std::vector<char> pushed;    // ... and carried a positive force (what StepMonitor takes)
  std::vector<char> in_phase;  // ... in a run of >= 2 such steps
  long k = 0;                      // steps taken: the state is at t_k = k h
};

struct Tally {
  double u_max = 0.0;  // largest |u_ref|
  long k_max = 0;      // its step
  double g_min = 0.0;  // most negative gap (0 if none)
  long impacts = 0;    // joints made for a contact that had none the step before, approaching
  long phases = 0;     // runs of >= 2 consecutive steps with a positive contact force
};

// The ODE objects of a run and what never changes during it.
struct Engine {
  const System& sys;
  const Config& config;
  double h;
  double bound;         // |u| above this is divergence
  double energy_bound;  // and so is a mechanical energy above this
  World world;
  std::vector<dBodyID> bodies;
  std::vector<dJointFeedback> feedback;  // one per contact; ODE writes it during the step
};

void set_up_world(Engine& s) {
  const dWorldID w = s.world.id();
  dWorldSetGravity(w, 0.0, 0.0, 0.0);
  dWorldSetERP(w, s.config.erp);
  dWorldSetCFM(w, s.config.cfm);
  dWorldSetContactMaxCorrectingVel(w, s.config.max_vel);
  dWorldSetContactSurfaceLayer(w, s.config.surface_layer);
  dWorldSetAutoDisableFlag(w, 0);
  dWorldSetDamping(w, 0.0, 0.0);
  if (s.config.stepper == Stepper::quickstep) {
    dWorldSetQuickStepNumIterations(w, s.config.iterations);
    dWorldSetQuickStepW(w, s.config.sor);
  }
}

// Bodies are created right to left. ODE keeps its bodies newest first and orders the
// rows of a step by walking them, so the contact rows reach its Dantzig solver left to
// right. The order matters only at exact ties, which ODE's Dantzig cannot pivot through:
// a row at w = 0 (bodies touching and moving alike) taken before the row that pushes it
// makes a zero step, and ODE gives up on the step (README, degenerate LCPs). Left to
// right suits the one kick of the case set, body 0 at the left end of a chain.
void add_bodies(Engine& s, const State& st) {
  s.bodies.assign(s.sys.bodies.size(), nullptr);
  for (std::size_t i = s.sys.bodies.size(); i-- > 0;) {
    const double m = s.sys.bodies[i].m;
    const dBodyID b = dBodyCreate(s.world.id());
    dMass mass;
    // Rotational inertia of a unit radius of gyration: rotation never starts (no torque).
    dMassSetParameters(&mass, m, 0.0, 0.0, 0.0, m, m, m, 0.0, 0.0, 0.0);
    dBodySetMass(b, &mass);
    dBodySetPosition(b, st.u[i], 0.0, 0.0);
    dBodySetLinearVel(b, st.v[i], 0.0, 0.0);
    dBodySetAutoDisableFlag(b, 0);
    s.bodies[i] = b;
  }
}

void update_gaps(const System& sys, State& st) {
  for (int j = 0; j < sys.n_contacts(); ++j) {
    const auto r = static_cast<std::size_t>(sys.right(j));
    const int left = sys.left(j);
    const double u_l = left == kWall ? 0.0 : st.u[static_cast<std::size_t>(left)];
    const double v_l = left == kWall ? 0.0 : st.v[static_cast<std::size_t>(left)];
    st.g[static_cast<std::size_t>(j)] = sys.delta + st.u[r] - u_l;
    st.rate[static_cast<std::size_t>(j)] = st.v[r] - v_l;
  }
}

void tally(const Engine& s, const State& st, Tally& t) {
  const double u = std::abs(st.u[static_cast<std::size_t>(s.sys.ref)]);
  if (u > t.u_max) {
    t.u_max = u;
    t.k_max = st.k;
  }
  for (double g : st.g) t.g_min = std::min(t.g_min, g);
}

void record(const Engine& s, const State& st, std::vector<double>& out) {
  out.push_back(static_cast<double>(st.k) * s.h);
  out.insert(out.end(), st.u.begin(), st.u.end());
  out.insert(out.end(), st.v.begin(), st.v.end());
  out.insert(out.end(), st.g.begin(), st.g.end());
  out.insert(out.end(), st.lambda.begin(), st.lambda.end());
}

// Spring, dashpot and ground load of each body at the start of the step. Returns false
// if a force is not finite (ODE must never see one).
bool apply_loads(const Engine& s, const State& st) {
  const double a_g = s.sys.pulse.accel(static_cast<double>(st.k) * s.h);
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const Body& b = s.sys.bodies[i];
    const double f = -b.k * st.u[i] - b.c * st.v[i] - b.m * a_g;
    if (!std::isfinite(f)) return false;
    dBodyAddForce(s.bodies[i], f, 0.0, 0.0);
  }
  return true;
}

// The contact joints of this step, made from the state at its start. Returns their number.
int make_contacts(Engine& s, State& st, Tally& t) {
  dJointGroupEmpty(s.world.contacts());
  int made = 0;
  for (int j = 0; j < s.sys.n_contacts(); ++j) {
    const auto jj = static_cast<std::size_t>(j);
    const double g = st.g[jj], rate = st.rate[jj];
    const bool make = s.config.detection == Detection::predicted ? g + s.h * rate <= 0.0 : g <= 0.0;
    if (make && !st.joint[jj] && rate < 0.0) ++t.impacts;
    st.joint[jj] = make ? 1 : 0;
    if (!make) continue;
    ++made;
    const dBodyID right = s.bodies[static_cast<std::size_t>(s.sys.right(j))];
    const int left = s.sys.left(j);
    dContact c{};
    c.surface.mode = dContactBounce;
    c.surface.mu = 0.0;
    c.surface.bounce = s.sys.eps;
    c.surface.bounce_vel = s.config.bounce_vel;
    // ODE's normal points into body 1: +x, so body 1 is the right body. The point lies on
    // the x axis, so the angular rows of the Jacobian are exactly zero.
    c.geom.pos[0] = st.u[static_cast<std::size_t>(s.sys.right(j))];
    c.geom.normal[0] = 1.0;
    c.geom.depth = std::max(0.0, -g);
    const dJointID joint = dJointCreateContact(s.world.id(), s.world.contacts(), &c);
    dJointAttach(joint, right, left == kWall ? nullptr : s.bodies[static_cast<std::size_t>(left)]);
    dJointSetFeedback(joint, &s.feedback[jj]);
  }
  return made;
}

// Reads the state ODE stepped to and the contact forces it used.
void observe(const Engine& s, State& st, Tally& t) {
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    st.u[i] = dBodyGetPosition(s.bodies[i])[0];
    st.v[i] = dBodyGetLinearVel(s.bodies[i])[0];
  }
  for (std::size_t j = 0; j < st.lambda.size(); ++j) {
    st.lambda[j] = st.joint[j] ? s.feedback[j].f1[0] : 0.0;
    const bool push = st.lambda[j] > 0.0;
    if (push && st.pushed[j] && !st.in_phase[j]) {
      ++t.phases;
      st.in_phase[j] = 1;
    }
    if (!push) st.in_phase[j] = 0;
    st.pushed[j] = push ? 1 : 0;
  }
  ++st.k;
  update_gaps(s.sys, st);
}

// Why the state counts as diverged, or nullptr.
const char* runaway(const Engine& s, const State& st) {
  for (double u : st.u)
    if (!(std::abs(u) <= s.bound)) return "|u| above 1e6 a_p/w_p^2";
  if (!(s.sys.energy(st.u.data(), st.v.data()) <= s.energy_bound)) return "energy above 1e6 times its scale";
  return nullptr;
}

// Every body must still be on the x axis, unrotated: the model's premise.
bool still_on_axis(const Engine& s) {
  for (const dBodyID b : s.bodies) {
    const dReal* p = dBodyGetPosition(b);
    const dReal* v = dBodyGetLinearVel(b);
    const dReal* w = dBodyGetAngularVel(b);
    const dReal* q = dBodyGetQuaternion(b);
    if (p[1] != 0.0 || p[2] != 0.0 || v[1] != 0.0 || v[2] != 0.0) return false;
    if (w[0] != 0.0 || w[1] != 0.0 || w[2] != 0.0) return false;
    if (q[0] != 1.0 || q[1] != 0.0 || q[2] != 0.0 || q[3] != 0.0) return false;
  }
  return true;
}

Result fail(Status status, std::string message) {
  Result r;
  r.status = status;
  r.message = std::move(message);
  return r;
}

bool finite_state(const State& st) {
  for (std::size_t i = 0; i < st.u.size(); ++i)
    if (!std::isfinite(st.u[i]) || !std::isfinite(st.v[i])) return false;
  return true;
}

// The start state of System, or rest when it gives none. False if it has the wrong size.
bool set_start(const System& sys, State& st) {
  const auto nb = static_cast<std::size_t>(sys.n_bodies());
  st.u.assign(nb, 0.0);
  st.v.assign(nb, 0.0);
  if (sys.u_start.empty() && sys.v_start.empty()) return true;
  if (sys.u_start.size() != nb || sys.v_start.size() != nb) return false;
  st.u = sys.u_start;
  st.v = sys.v_start;
  return true;
}

Result run(const System& sys, const Settings& set, const Config& config) {
  if (std::string bad = check_config(config); !bad.empty()) return fail(Status::failed, "config: " + bad);
  if (std::string bad = check_step(set, kDefaultSteps); !bad.empty()) return fail(Status::failed, bad);
  const int nb = sys.n_bodies(), nc = sys.n_contacts();
  for (const Body& b : sys.bodies)
    if (!(b.m > 0.0 && std::isfinite(b.m))) return fail(Status::failed, "every body needs a finite positive mass");
  State st;
  if (!set_start(sys, st)) return fail(Status::failed, "start state: needs one u and one v per body");
  for (auto* vec : {&st.g, &st.rate, &st.lambda}) vec->assign(static_cast<std::size_t>(nc), 0.0);
  for (auto* vec : {&st.joint, &st.pushed, &st.in_phase}) vec->assign(static_cast<std::size_t>(nc), 0);
  update_gaps(sys, st);

  const double h = time_step(sys, set, kDefaultSteps);
  const long n = step_count(sys.t_end, h);
  const long cap = set.step_cap > 0 ? set.step_cap : kDefaultStepCap;
  if (n > cap) {
    Result r = fail(Status::step_cap,
                    "the run needs " + std::to_string(n) + " steps, more than the cap " + std::to_string(cap));
    r.step = h;
    return r;
  }
  if (!prepare_thread()) return fail(Status::failed, "ODE could not be initialised on this thread");

  Engine s{sys, config, h, 1e6 * sys.length_scale(), kDivergedEnergy * sys.energy_scale(), {}, {}, {}};
  if (!s.world.ok()) return fail(Status::failed, "ODE could not create a world");
  set_up_world(s);
  add_bodies(s, st);
  s.feedback.assign(static_cast<std::size_t>(nc), dJointFeedback{});
  (void)take_messages();  // only this run's messages go into its result

  Result res;
  res.step = h;
  Tally t;
  tally(s, st, t);
  std::optional<StepMonitor> monitor;
  if (set.monitor) monitor.emplace(sys);
  const bool recording = set.history_samples > 0;
  if (recording) {
    res.history.n_bodies = nb;
    res.history.n_contacts = nc;
    res.history.data.reserve(static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(res.history.row_size()));
    record(s, st, res.history.data);
  }

  const long lcp_failures_before = lcp_failures();
  const char* diverged_by = "";
  Deadline deadline(set);
  const bool quick = config.stepper == Stepper::quickstep;
  while (st.k < n) {
    if (!apply_loads(s, st)) {
      res.status = Status::nan;
      break;
    }
    const int rows = make_contacts(s, st, t);
    const int stepped = quick ? quick_step(s.world.id(), h, rows) : dWorldStep(s.world.id(), h);
    if (stepped == 0) {
      res.status = Status::failed;
      res.message = "ODE could not step (working memory)";
      break;
    }
    observe(s, st, t);
    if (lcp_failures() != lcp_failures_before) {
      res.status = Status::failed;
      res.message = "ODE's Dantzig LCP gave up (degenerate pivot) at step " + std::to_string(st.k) +
                    ": the contact forces of that step are wrong";
      break;
    }
    if (!finite_state(st)) {
      res.status = Status::nan;
      break;
    }
    // A diverging state is still seen by the monitor: its energy excess shows the growth.
    if (monitor) {
      const double t0 = static_cast<double>(st.k - 1) * h, t1 = static_cast<double>(st.k) * h;
      monitor->step(h, sys.pulse.mean(t0, t1), st.u.data(), st.v.data(), st.pushed.data());
    }
    if (const char* why = runaway(s, st)) {
      res.status = Status::diverged;
      diverged_by = why;
      break;
    }
    tally(s, st, t);
    if (recording) record(s, st, res.history.data);
    if (st.k < n && deadline.passed(st.k)) {
      res.status = Status::time_limit;
      res.message = deadline.reason() + " at t = " + std::to_string(static_cast<double>(st.k) * h);
      break;
    }
  }

  res.steps = st.k;
  res.impacts = t.impacts;
  res.contact_phases = t.phases;
  res.min_gap = t.g_min < 0.0 ? t.g_min : std::numeric_limits<double>::infinity();
  if (monitor) monitor->finish(res);
  if (res.status == Status::nan || res.status == Status::diverged) {
    std::ostringstream msg;
    msg << (res.status == Status::nan ? "non-finite state or force" : diverged_by) << " at step "
        << st.k << " (t = " << static_cast<double>(st.k) * h << ", w_max h = " << 2.0 * std::numbers::pi * h / sys.t_min
        << ")";
    res.message = msg.str();
  }
  if (res.status == Status::ok && !still_on_axis(s)) {
    res.status = Status::failed;
    res.message = "a body left the x axis or rotated";
  }
  if (std::string notes = take_messages(); !notes.empty())
    res.message += (res.message.empty() ? "" : "; ") + notes;
  if (res.status != Status::ok) return res;
  res.pi1 = sys.pi1(t.u_max);
  res.t_max = static_cast<double>(t.k_max) * h;
  return res;
}

Result guarded(const System& sys, const Settings& set, const Config& config) {
  try {
    return run(sys, set, config);
  } catch (const std::exception& e) {
    return fail(Status::failed, e.what());
  }
}

}  // namespace

Result solve(const System& system, const Settings& settings) {
  const std::optional<Config> config = find_variant(settings.variant);
  if (!config) return fail(Status::failed, "unknown variant " + settings.variant);
  return guarded(system, settings, *config);
}

Result solve_with(const System& system, const Settings& settings, const Config& config) {
  return guarded(system, settings, config);
}

std::string describe(const Settings& settings) {
  const std::optional<Config> config = find_variant(settings.variant);
  if (!config) return "variant=" + settings.variant;
  return describe(*config, step_setting(settings));
}

std::string check(const Settings& settings) {
  if (!find_variant(settings.variant)) {
    std::string known;
    for (const Config& c : variants()) known += (known.empty() ? "" : ", ") + std::string(c.name);
    return "variant: unknown '" + settings.variant + "' (known: " + known + ")";
  }
  if (std::string bad = check_step(settings, kDefaultSteps); !bad.empty()) return bad;
  return check_limits(settings);
}

}  // namespace pb::ode
