#include "solvers/bullet/bullet_solver.hpp"

#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "solvers/bullet/engine.hpp"
#include "solvers/monitor.hpp"

namespace pb::bullet {

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

// Fixed h, and the first step count whose end reaches t_end (to within 1e-9 of a step, so
// that t_end = n h up to round-off does not add a step): the same count as moreau-jean.
long step_count(double t_end, double h) { return static_cast<long>(std::ceil(t_end / h - 1e-9)); }

std::size_t ix(int i) { return static_cast<std::size_t>(i); }

struct Tally {
  double u_max = 0.0;  // largest |u_ref| over the steps
  long k_max = 0;      // its step
  double g_min = 0.0;  // most negative gap (0 if none)
  long impacts = 0;    // contacts that got a manifold point while approaching
  long phases = 0;     // runs of >= 2 consecutive steps with a positive impulse
  std::vector<char> pushed, in_phase;  // per contact, last step
};

void tally_state(const System& s, const World& w, long k, Tally& t) {
  const double u = std::abs(w.u(s.ref));
  if (u > t.u_max) {
    t.u_max = u;
    t.k_max = k;
  }
  for (int j = 0; j < s.n_contacts(); ++j) t.g_min = std::min(t.g_min, w.gap(j));
}

// One history row: t, u, v, g, lambda = impulse / h (History in solvers/solver.hpp).
void record(const System& s, const World& w, double t, double h, bool with_impulse, std::vector<double>& out) {
  out.push_back(t);
  for (int i = 0; i < s.n_bodies(); ++i) out.push_back(w.u(i));
  for (int i = 0; i < s.n_bodies(); ++i) out.push_back(w.v(i));
  for (int j = 0; j < s.n_contacts(); ++j) out.push_back(w.gap(j));
  for (int j = 0; j < s.n_contacts(); ++j) out.push_back(with_impulse ? w.impulse(j) / h : 0.0);
}

// Reads the state after a step into u, v (double: what the monitor takes); false if it is
// not finite.
bool read_state(const World& w, std::vector<double>& u, std::vector<double>& v) {
  for (std::size_t i = 0; i < u.size(); ++i) {
    u[i] = w.u(static_cast<int>(i));
    v[i] = w.v(static_cast<int>(i));
    if (!std::isfinite(u[i]) || !std::isfinite(v[i])) return false;
  }
  return true;
}

// Why a finite state counts as diverged, or nullptr.
const char* runaway(const System& s, const std::vector<double>& u, const std::vector<double>& v, double bound,
                    double energy_bound) {
  for (double x : u)
    if (std::abs(x) > bound) return "|u| above 1e6 a_p/w_p^2";
  if (!(s.energy(u.data(), v.data()) <= energy_bound)) return "energy above 1e6 times its scale";
  return nullptr;
}

Result run(const System& sys, const Settings& set, const Config& config) {
  Result res;
  const int nb = sys.n_bodies(), nc = sys.n_contacts();
  if (std::string bad = check_step(set, kDefaultSteps); !bad.empty()) {
    res.status = Status::failed;
    res.message = bad;
    return res;
  }
  const double h = time_step(sys, set, kDefaultSteps);
  res.step = h;
  const long n = step_count(sys.t_end, h);
  const long cap = set.step_cap > 0 ? set.step_cap : kDefaultStepCap;
  if (n > cap) {
    res.status = Status::step_cap;
    res.message = "the run needs " + std::to_string(n) + " steps, more than the cap " + std::to_string(cap);
    return res;
  }
  std::vector<double> u(ix(nb), 0.0), v(ix(nb), 0.0);  // the state at the end of each step
  if (!sys.u_start.empty() || !sys.v_start.empty()) {
    if (sys.u_start.size() != ix(nb) || sys.v_start.size() != ix(nb)) {
      res.status = Status::failed;
      res.message = "start state: needs one u and one v per body";
      return res;
    }
    u = sys.u_start;
    v = sys.v_start;
  }

  World world(sys, config, h, u, v);
  Tally tally;
  tally.pushed.assign(ix(nc), 0);
  tally.in_phase.assign(ix(nc), 0);
  tally_state(sys, world, 0, tally);
  std::vector<double> rate(ix(nc), 0.0);
  std::optional<StepMonitor> monitor;
  if (set.monitor) monitor.emplace(sys);

  const bool recording = set.history_samples > 0;
  if (recording) {
    res.history.n_bodies = nb;
    res.history.n_contacts = nc;
    res.history.data.reserve(static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(res.history.row_size()));
    record(sys, world, 0.0, h, false, res.history.data);
  }

  const double bound = 1e6 * sys.length_scale(), energy_bound = kDivergedEnergy * sys.energy_scale();
  Deadline deadline(set);
  long k = 0;
  while (k < n) {
    for (int j = 0; j < nc; ++j) rate[ix(j)] = world.gap_rate(j);  // approach speed at t_k
    world.step(static_cast<double>(k) * h);
    ++k;
    for (int j = 0; j < nc; ++j) {
      if (world.added(j) && rate[ix(j)] < 0.0) ++tally.impacts;
      const char pushing = world.impulse(j) > 0.0 ? 1 : 0;
      const char starts = pushing && tally.pushed[ix(j)] && !tally.in_phase[ix(j)];
      tally.phases += starts;
      tally.in_phase[ix(j)] = (tally.in_phase[ix(j)] || starts) && pushing;
      tally.pushed[ix(j)] = pushing;
    }
    const bool finite = read_state(world, u, v);
    // A diverging state is still seen by the monitor: its energy excess shows the growth.
    if (monitor && finite) {
      const double t0 = static_cast<double>(k - 1) * h, t1 = static_cast<double>(k) * h;
      monitor->step(h, sys.pulse.mean(t0, t1), u.data(), v.data(), tally.pushed.data());
    }
    const char* why = finite ? runaway(sys, u, v, bound, energy_bound) : "non-finite state";
    if (why) {
      res.status = finite ? Status::diverged : Status::nan;
      std::ostringstream msg;
      msg << why << " at step " << k
          << " (t = " << static_cast<double>(k) * h << ", w_max h = " << 2.0 * std::numbers::pi * h / sys.t_min
          << ")";
      res.message = msg.str();
      break;
    }
    tally_state(sys, world, k, tally);
    if (recording) record(sys, world, static_cast<double>(k) * h, h, true, res.history.data);
    if (k < n && deadline.passed(k)) {
      res.status = Status::time_limit;
      res.message = deadline.reason() + " at t = " + std::to_string(static_cast<double>(k) * h);
      break;
    }
  }

  res.steps = k;
  res.impacts = tally.impacts;
  res.contact_phases = tally.phases;
  res.min_gap = tally.g_min < 0.0 ? tally.g_min : std::numeric_limits<double>::infinity();
  if (monitor) monitor->finish(res);
  if (const int fb = world.fallbacks(); fb > 0) {
    if (!res.message.empty()) res.message += "; ";
    res.message += "the MLCP solver failed in " + std::to_string(fb) + " steps (Bullet fell back to sequential impulse)";
  }
  if (res.status != Status::ok) return res;
  res.pi1 = sys.pi1(tally.u_max);
  res.t_max = static_cast<double>(tally.k_max) * h;
  return res;
}

}  // namespace

Result solve_with(const System& system, const Settings& settings, const Config& config) {
  try {
    return run(system, settings, config);
  } catch (const std::exception& e) {
    Result res;
    res.status = Status::failed;
    res.message = e.what();
    return res;
  }
}

Result solve(const System& system, const Settings& settings) {
  const std::optional<Config> config = find_variant(settings.variant);
  if (!config) {
    Result res;
    res.status = Status::failed;
    res.message = "unknown variant '" + settings.variant + "'";
    return res;
  }
  return solve_with(system, settings, *config);
}

std::string describe(const Settings& settings) {
  const std::optional<Config> config = find_variant(settings.variant);
  if (!config) return "variant=" + settings.variant + ";unknown";
  return describe(*config, step_setting(settings));
}

std::string check(const Settings& settings) {
  if (!find_variant(settings.variant))
    return "variant: unknown bullet variant '" + settings.variant + "' (one of " + variant_names() + ")";
  if (std::string bad = check_step(settings, kDefaultSteps); !bad.empty()) return bad;
  return check_limits(settings);
}

}  // namespace pb::bullet
