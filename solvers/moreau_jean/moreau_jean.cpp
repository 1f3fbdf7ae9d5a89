#include "solvers/moreau_jean/moreau_jean.hpp"

#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>

#include "solvers/moreau_jean/stepper.hpp"

namespace pb::moreau_jean {

namespace {

// Steps between two looks at the wall clock; a multiple of kResync, so chunking never
// changes where the pulse recurrence is resynchronised (results do not depend on it).
constexpr long kChunk = 1L << 16;
static_assert(kChunk % kResync == 0);

int steps_per_period(const Settings& s) { return s.steps == 0 ? kDefaultSteps : s.steps; }

template <int NB, int NC>
Result run(const System& sys, const Settings& set, const InitialState* start) {
  using VecB = typename Scheme<NB, NC>::VecB;
  using VecC = typename Scheme<NB, NC>::VecC;
  Result res;
  const double h = sys.step(steps_per_period(set));
  const long n = step_count(sys.t_end, h);
  const long cap = set.step_cap > 0 ? set.step_cap : kDefaultStepCap;
  if (n > cap) {
    res.status = Status::step_cap;
    res.message = "the run needs " + std::to_string(n) + " steps, more than the cap " + std::to_string(cap);
    return res;
  }

  const Scheme<NB, NC> sc = make_scheme<NB, NC>(sys, h, set.theta, set.gamma);
  VecB u0 = VecB::Zero(), v0 = VecB::Zero();
  if (start) {
    if (start->u.size() != NB || start->v.size() != NB) {
      res.status = Status::failed;
      res.message = "initial state: needs one u and one v per body";
      return res;
    }
    for (int i = 0; i < NB; ++i) {
      u0(i) = start->u[static_cast<std::size_t>(i)];
      v0(i) = start->v[static_cast<std::size_t>(i)];
    }
  }
  State<NB, NC> st = make_state(sc, u0, v0);
  Tally tally;
  tally_state(sc, st, tally);

  const bool recording = set.history_samples > 0;
  std::vector<double>* rows = recording ? &res.history.data : nullptr;
  if (recording) {
    res.history.n_bodies = NB;
    res.history.n_contacts = NC;
    rows->reserve(static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(res.history.row_size()));
    record(sc, st, VecC::Zero().eval(), *rows);
  }

  const auto started = std::chrono::steady_clock::now();
  bool finite = true;
  while (st.k < n) {
    const long end = std::min(n, st.k + kChunk);
    finite =
        recording ? advance<NB, NC, true>(sc, st, tally, end, rows) : advance<NB, NC, false>(sc, st, tally, end, rows);
    if (!finite) break;
    if (set.time_limit > 0.0 && st.k < n &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() > set.time_limit) {
      res.status = Status::timeout;
      res.message = "time limit reached at t = " + std::to_string(static_cast<double>(st.k) * h);
      break;
    }
  }

  res.steps = st.k;
  res.impacts = tally.impacts;
  res.contact_phases = tally.phases;
  res.min_gap = tally.g_min < 0.0 ? tally.g_min : std::numeric_limits<double>::infinity();
  if (!finite) {
    res.status = st.q.allFinite() && st.v.allFinite() ? Status::diverged : Status::nan;
    std::ostringstream msg;
    msg << (res.status == Status::nan ? "non-finite state" : "|u| above 1e6 a_p/w_p^2") << " at step " << st.k
        << " (t = " << static_cast<double>(st.k) * h << ")";
    res.message = msg.str();
  }
  if (res.status != Status::ok) return res;
  res.pi1 = sys.pi1(tally.u_max);
  res.t_max = static_cast<double>(tally.k_max) * h;
  return res;
}

Result dispatch(const System& sys, const Settings& set, const InitialState* start) {
  try {
    const int nb = sys.n_bodies(), nc = sys.n_contacts();
    if (nb == 1 && nc == 1) return run<1, 1>(sys, set, start);  // wall
    if (nb == 2 && nc == 1) return run<2, 1>(sys, set, start);  // pair
    if (nb == 3 && nc == 2) return run<3, 2>(sys, set, start);  // row3
    if (nb == 1 && nc == 0) return run<1, 0>(sys, set, start);  // body 0 alone (no-contact response)
    Result res;
    res.status = Status::failed;
    res.message = "no fixed-size path for " + std::to_string(nb) + " bodies and " + std::to_string(nc) + " contacts";
    return res;
  } catch (const std::exception& e) {
    Result res;
    res.status = Status::failed;
    res.message = e.what();
    return res;
  }
}

}  // namespace

Result solve(const System& system, const Settings& settings) { return dispatch(system, settings, nullptr); }

Result solve_from(const System& system, const Settings& settings, const InitialState& start) {
  return dispatch(system, settings, &start);
}

std::string describe(const Settings& settings) {
  std::ostringstream out;
  out << "steps=" << steps_per_period(settings) << ";theta=" << settings.theta << ";gamma=" << settings.gamma;
  return out.str();
}

std::string check(const Settings& settings) {
  if (!settings.variant.empty()) return "variant: moreau-jean has no variants";
  if (settings.steps < 0) return "steps: must be >= 1 (0: the default " + std::to_string(kDefaultSteps) + ")";
  if (!(settings.theta >= 0.5 && settings.theta <= 1.0)) return "theta: must be in [0.5, 1]";
  if (!(settings.gamma >= 0.0 && settings.gamma <= 1.0)) return "gamma: must be in [0, 1]";
  if (settings.step_cap < 0) return "step_cap: must be >= 0 (0: the solver's own cap)";
  if (!(settings.time_limit >= 0.0)) return "time_limit: must be >= 0 (0: none)";
  return {};
}

}  // namespace pb::moreau_jean
