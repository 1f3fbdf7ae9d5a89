#include "solvers/moreau_jean/moreau_jean.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>

#include "cases/text.hpp"
#include "kit/fixed_step.hpp"
#include "kit/monitor.hpp"
#include "solvers/moreau_jean/dynamic.hpp"
#include "solvers/moreau_jean/stepper.hpp"
#include "kit/run_limits.hpp"
#include "solvers/moreau_jean/yielding.hpp"

namespace pb::moreau_jean {

namespace {

// Steps between two looks at the wall clock for the fixed-size path (the any-size path
// divides it by the number of bodies); a multiple of kResync, so chunking never changes
// where the pulse recurrence is resynchronised (results do not depend on it).
constexpr long kChunk = 1L << 16;
static_assert(kChunk % kResync == 0);

// The load rule a variant names: "" and "step-mean" the default, "end-samples" Siconos'.
bool known_variant(std::string_view v) { return v.empty() || v == kStepMean || v == kEndSamples; }

LoadRule load_rule(const Settings& set) {
  return set.variant == kEndSamples ? LoadRule::end_samples : LoadRule::step_mean;
}

// Start value i of System::u_start or v_start: empty means rest (a System made by hand).
double start_value(const std::vector<double>& x, int i) { return x.empty() ? 0.0 : x[static_cast<std::size_t>(i)]; }

// Calls advance(k_end) on chunks of `chunk` steps until the state is at step n, and looks
// at the Deadline between chunks. False if the state blew up.
template <class Advance>
bool run_chunks(const long& k, long n, long chunk, double h, const Settings& set, Result& res, Advance&& advance) {
  Deadline deadline(set);
  while (k < n) {
    if (!advance(std::min(n, k + chunk))) return false;
    if (k < n && deadline.passed(k)) {
      res.status = Status::time_limit;
      res.message = deadline.reason() + " at t = " + std::to_string(static_cast<double>(k) * h);
      break;
    }
  }
  return true;
}

// Counts, status and Pi1 once the loop has stopped at step k; `finite`: the loop's own
// divergence test passed; `state_finite`: no NaN or inf in the state.
template <class Monitor>
void finish(const System& sys, const Tally& tally, long k, double h, bool finite, bool state_finite,
            const std::optional<Monitor>& monitor, Result& res) {
  if (monitor) monitor->finish(res);
  if (!finite) res.status = state_finite ? Status::diverged : Status::nan;
  finish_steps(sys, tally, k, h, nullptr, res);
}

template <int NB, int NC>
Result run_fixed(const System& sys, const Settings& set, double h, long n, Result res) {
  using VecB = typename Scheme<NB, NC>::VecB;
  using VecC = typename Scheme<NB, NC>::VecC;
  const Scheme<NB, NC> sc = make_scheme<NB, NC>(sys, h, set.theta, set.gamma, load_rule(set));
  VecB u0, v0;
  for (int i = 0; i < NB; ++i) {
    u0(i) = start_value(sys.u_start, i);
    v0(i) = start_value(sys.v_start, i);
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
  std::optional<FixedStepMonitor<NB, NC>> monitor;
  if (set.monitor) monitor.emplace(sys, h);
  FixedStepMonitor<NB, NC>* m = monitor ? &*monitor : nullptr;

  const bool finite = run_chunks(st.k, n, kChunk, h, set, res, [&](long end) {
    if (recording)
      return m ? advance<NB, NC, true, true>(sc, st, tally, end, rows, m)
               : advance<NB, NC, true, false>(sc, st, tally, end, rows, m);
    return m ? advance<NB, NC, false, true>(sc, st, tally, end, rows, m)
             : advance<NB, NC, false, false>(sc, st, tally, end, rows, m);
  });
  finish(sys, tally, st.k, h, finite, st.q.allFinite() && st.v.allFinite(), monitor, res);
  return res;
}

Result run_dynamic(const System& sys, const Settings& set, double h, long n, Result res) {
  const dynamic::Scheme sc = dynamic::make_scheme(sys, h, set.theta, set.gamma, load_rule(set));
  dynamic::Work work = dynamic::make_work(sc);
  Tally tally;
  std::vector<double>* rows = set.history_samples > 0 ? &res.history.data : nullptr;
  dynamic::State st = dynamic::start_run(sc, sys, n, work, tally, res, rows);
  std::optional<StepMonitor> monitor;
  if (set.monitor) monitor.emplace(sys);
  StepMonitor* m = monitor ? &*monitor : nullptr;

  // About kChunk body-steps between looks at the clock, in whole resynchronisation periods.
  const long chunk = std::max(kResync, kChunk / (sc.nb + 1) / kResync * kResync);
  const bool finite = run_chunks(st.k, n, chunk, h, set, res,
                            [&](long end) { return dynamic::advance(sc, st, work, tally, end, rows, m); });
  finish(sys, tally, st.k, h, finite, st.q.allFinite() && st.v.allFinite(), monitor, res);
  return res;
}

Result dispatch(const System& sys, const Settings& set, bool force_dynamic) {
  if (!known_variant(set.variant)) return failed("variant: unknown '" + clip(set.variant) + "'");
  try {
    StepPlan plan;
    Result res = plan_steps(sys, set, kDefaultSteps, kDefaultStepCap, plan);
    if (res.status != Status::ok) return res;
    const double h = plan.h;
    const long n = plan.n;
    if (sys.yields()) return run_yielding(sys, set, h, n, std::move(res));
    if (!force_dynamic) {
      const int nb = sys.n_bodies(), nc = sys.n_contacts();
      if (nb == 1 && nc == 1) return run_fixed<1, 1>(sys, set, h, n, std::move(res));  // wall
      if (nb == 2 && nc == 1) return run_fixed<2, 1>(sys, set, h, n, std::move(res));  // pair, chain of 2
      if (nb == 3 && nc == 2) return run_fixed<3, 2>(sys, set, h, n, std::move(res));  // row3, chain of 3
      if (nb == 1 && nc == 0) return run_fixed<1, 0>(sys, set, h, n, std::move(res));  // body 0 alone
    }
    return run_dynamic(sys, set, h, n, std::move(res));
  } catch (const std::exception& e) {
    return failed(e.what());
  }
}

}  // namespace

Result solve(const System& system, const Settings& settings) { return dispatch(system, settings, false); }

Result solve_dynamic(const System& system, const Settings& settings) { return dispatch(system, settings, true); }

std::string describe(const Settings& settings) {
  NamedValues out;
  add_step(out, settings, kDefaultSteps);
  out.add("theta", settings.theta).add("gamma", settings.gamma);
  if (settings.variant == kEndSamples) out.add("load", "end-samples");
  return out.json();
}

std::vector<VariantInfo> variant_list() {
  return {{kStepMean, "a step's load is the exact mean of a_g over the step"},
          {kEndSamples, "a step's load is (1 - theta) a_g(t_k) + theta a_g(t_k+1), as Siconos takes it"}};
}

std::string check(const Settings& settings) {
  if (!known_variant(settings.variant))
    return "variant: unknown '" + settings.variant + "' (known: " + std::string(kStepMean) + " (default), " +
           std::string(kEndSamples) + ")";
  if (std::string step = check_step(settings, kDefaultSteps); !step.empty()) return step;
  if (std::string theta = check_theta_method(settings); !theta.empty()) return theta;
  return {};
}

}  // namespace pb::moreau_jean
