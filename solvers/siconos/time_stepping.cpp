// The time-stepping variants: Siconos' TimeStepping with MoreauJeanOSI(theta, gamma) and an
// LCP at the velocity level, one step at a time, so that every step is seen: the state, the
// impulses, the index set Siconos chose and the path its LCP driver took.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "solvers/fixed_step.hpp"
#include "solvers/siconos/model.hpp"

namespace pb::siconos {

namespace {

void count(const engine::LcpCall& call, LcpPaths& paths) {
  if (!call.called) return;
  ++paths.calls;
  if (call.q_nonnegative)
    ++paths.trivial;
  else if (call.rows == 1)
    ++paths.one_row;
  else
    ++paths.solver;
  if (call.counter_written) ++paths.written;
}

std::string paths_message(const LcpPaths& p, bool enumeration) {
  std::ostringstream out;
  out << "lcp: " << p.calls << " calls: " << p.trivial << " with q >= 0 (z = 0, no solver), " << p.one_row
      << " of one row (z = -q/M, no solver), " << p.solver << " by " << (enumeration ? "enumeration" : "Lemke");
  return out.str();
}

// Siconos' TimeStepping behind the shared step loop (solvers/fixed_step.hpp), one step at a
// time, so that every step is seen: the state, the impulses, the index set Siconos chose
// and the path its LCP driver took.
class Engine : public StepEngine {
 public:
  Engine(const System& sys, const Settings& set, const StepPlan& plan, bool enumeration)
      : StepEngine(sys),
        sys_(sys),
        units_(units_of(sys)),
        // Siconos' horizon half a step past the last step, so that round-off cannot drop it.
        run_(model_spec(sys, plan.h, (static_cast<double>(plan.n) + 0.5) * plan.h), plan.h / units_.time, set.theta,
             set.gamma, enumeration),
        force_unit_(units_.velocity() / plan.h),  // of an impulse in Siconos' units, per unit mass
        enumeration_(enumeration),
        n_(plan.n),
        st_(sys),
        active_(static_cast<std::size_t>(sys.n_contacts()), 0) {
    read_state();
  }

  StepOutcome step(long k, Result& res) override {
    // The index set of this step, chosen by Siconos from the state at t_k.
    for (int j = 0; j < sys_.n_contacts(); ++j) {
      const auto jj = static_cast<std::size_t>(j);
      const bool active = run_.active(j);
      out_.entered[jj] = active && !active_[jj] ? 1 : 0;
      active_[jj] = active ? 1 : 0;
    }
    bool stepped = false;
    try {
      stepped = run_.step();
    } catch (const std::exception& e) {
      res.status = Status::failed;
      res.message = std::string("Siconos: ") + e.what() + " (at step " + std::to_string(k + 1) + ")";
      return StepOutcome::refused;
    }
    if (!stepped) {
      res.status = Status::failed;
      res.message = "Siconos ended the run at step " + std::to_string(k) + " of " + std::to_string(n_);
      return StepOutcome::refused;
    }
    count(run_.last_lcp(), paths_);
    if (run_.last_lcp().info != 0) {
      res.status = Status::failed;
      res.message = "Siconos' LCP solver returned info " + std::to_string(run_.last_lcp().info) + " at step " +
                    std::to_string(k + 1);
      return StepOutcome::taken_then_stop;
    }
    for (int j = 0; j < sys_.n_contacts(); ++j) out_.force[static_cast<std::size_t>(j)] = run_.impulse(j) * force_unit_;
    read_state();
    return StepOutcome::taken;
  }

  void finish(Result& res) override {
    if (res.status == Status::ok) res.message = paths_message(paths_, enumeration_);
  }
  const LcpPaths& paths() const { return paths_; }

 private:
  void read_state() {
    st_.read(run_, sys_, units_);
    out_.u = st_.u;
    out_.v = st_.v;
  }

  const System& sys_;
  Units units_;
  engine::TimeStepper run_;
  double force_unit_;
  bool enumeration_;
  long n_;
  State st_;
  std::vector<char> active_;  // per contact: in the index set of the last step
  LcpPaths paths_;
};

}  // namespace

Result run_time_stepping(const System& sys, const Settings& set, bool enumeration, LcpPaths* paths_out) {
  if (std::string bad = check_system(sys); !bad.empty()) return stopped(Status::failed, bad);
  StepPlan plan;
  if (Result r = plan_steps(sys, set, kDefaultSteps, kDefaultStepCap, plan); r.status != Status::ok) return r;
  Engine engine(sys, set, plan, enumeration);
  Result res = run_steps(sys, set, plan, engine);
  if (paths_out) *paths_out = engine.paths();
  return res;
}

}  // namespace pb::siconos
