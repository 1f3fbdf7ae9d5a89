// The time-stepping variants: a Siconos time-stepping simulation (TimeStepping with
// MoreauJeanOSI, SchatzmanPaoliOSI or MoreauJeanBilbaoOSI; TimeSteppingD1Minus;
// TimeSteppingCombinedProjection; TimeSteppingDirectProjection), one step at a time, so that
// every step is seen: the state, the impulses, the index set Siconos chose and (MoreauJeanOSI)
// the path its LCP driver took.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "kit/fixed_step.hpp"
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

bool projects(engine::Integrator i) {
  return i == engine::Integrator::combined_projection || i == engine::Integrator::direct_projection;
}

// Where a MoreauJeanBilbaoOSI run equals, bit for bit, the same model with no ground load, the
// integrator left the load out (Siconos 4.4's MoreauJeanBilbaoOSI::computeFreeState forms the
// free velocity from the stiffness, the damping and the state alone). A run whose ground load
// is zero throughout has no such twin to tell it from.
constexpr const char* kBilbaoIgnoresTheLoad =
    "MoreauJeanBilbaoOSI left the ground load out: every state of the run equals, bit for bit, that of the same "
    "model with no load (Siconos 4.4's computeFreeState uses only the stiffness, the damping and the state, never "
    "F_ext)";

// A Siconos time-stepping simulation behind the shared step loop (kit/fixed_step.hpp),
// one step at a time.
class Engine : public StepEngine {
 public:
  Engine(const System& sys, const StepPlan& plan, const engine::StepperOptions& options)
      : StepEngine(sys),
        sys_(sys),
        units_(units_of(sys)),
        options_(options),
        // Siconos' horizon half a step past the last step, so that round-off cannot drop it.
        spec_(model_spec(sys, plan.h, (static_cast<double>(plan.n) + 0.5) * plan.h)),
        run_(spec_, plan.h / units_.time, options),
        force_unit_(units_.velocity() / plan.h),  // of an impulse in Siconos' units, per unit mass
        n_(plan.n),
        st_(sys),
        active_(static_cast<std::size_t>(sys.n_contacts()), 0) {
    if (options.integrator == engine::Integrator::bilbao && spec_.amplitude != 0.0) {
      engine::ModelSpec unloaded = spec_;
      unloaded.amplitude = 0.0;
      unloaded.sampler = nullptr;
      twin_.emplace(unloaded, plan.h / units_.time, options);
    }
    read_state();
  }

  StepOutcome step(long k, Result& res) override {
    // The index set of this step, chosen by Siconos from the state at t_k; a scheme whose LCP
    // takes every contact (Schatzman-Paoli) enters a contact where its impulse starts.
    if (run_.has_index_set())
      for (int j = 0; j < sys_.n_contacts(); ++j) {
        const auto jj = static_cast<std::size_t>(j);
        const bool active = run_.active(j);
        out_.entered[jj] = active && !active_[jj] ? 1 : 0;
        active_[jj] = active ? 1 : 0;
      }
    bool stepped = false;
    try {
      stepped = run_.step();
      if (twin_) twin_->step();
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
    if (options_.integrator == engine::Integrator::moreau_jean) count(run_.last_lcp(), paths_);
    if (run_.last_lcp().info != 0) {
      res.status = Status::failed;
      res.message = "Siconos' LCP solver returned info " + std::to_string(run_.last_lcp().info) + " at step " +
                    std::to_string(k + 1);
      return StepOutcome::taken_then_stop;
    }
    for (int j = 0; j < sys_.n_contacts(); ++j) {
      const auto jj = static_cast<std::size_t>(j);
      out_.force[jj] = run_.impulse(j) * force_unit_;
      if (!run_.has_index_set()) {
        const bool pushing = out_.force[jj] > 0.0;
        out_.entered[jj] = pushing && !active_[jj] ? 1 : 0;
        active_[jj] = pushing ? 1 : 0;
      }
    }
    read_state();
    if (twin_ && !same_as_twin()) twin_.reset();  // the load mattered: no twin needed
    return StepOutcome::taken;
  }

  void finish(Result& res) override {
    if (res.status != Status::ok) return;
    if (twin_) {
      res.status = Status::failed;
      res.message = kBilbaoIgnoresTheLoad;
      return;
    }
    if (options_.integrator == engine::Integrator::moreau_jean) {
      res.message = paths_message(paths_, options_.enumeration);
    } else if (projects(options_.integrator)) {
      std::ostringstream msg;
      msg << "projection: " << run_.projection_iterations() << " iterations, largest violation left "
          << run_.max_violation() * units_.length << " (the tolerance: " << options_.projection_tol * units_.length
          << ")";
      res.message = msg.str();
    }
  }
  const LcpPaths& paths() const { return paths_; }

 private:
  void read_state() {
    st_.read(run_, sys_, units_);
    out_.u = st_.u;
    out_.v = st_.v;
  }

  bool same_as_twin() const {
    std::vector<double>& u = twin_u_;
    std::vector<double>& v = twin_v_;
    u.resize(st_.u.size());
    v.resize(st_.v.size());
    twin_->state(u.data(), v.data());
    for (std::size_t i = 0; i < u.size(); ++i)
      if (u[i] * units_.length != st_.u[i] || v[i] * units_.velocity() != st_.v[i]) return false;
    return true;
  }

  const System& sys_;
  Units units_;
  engine::StepperOptions options_;
  engine::ModelSpec spec_;
  engine::TimeStepper run_;
  std::optional<engine::TimeStepper> twin_;  // bilbao: the same model, unloaded
  mutable std::vector<double> twin_u_, twin_v_;
  double force_unit_;
  long n_;
  State st_;
  std::vector<char> active_;  // per contact: in the index set (or pushing) in the last step
  LcpPaths paths_;
};

}  // namespace

Result run_time_stepping(const System& sys, const Settings& set, const engine::StepperOptions& options,
                         LcpPaths* paths_out) {
  if (std::string bad = check_system(sys); !bad.empty()) return stopped(Status::failed, bad);
  StepPlan plan;
  if (Result r = plan_steps(sys, set, kDefaultSteps, kDefaultStepCap, plan); r.status != Status::ok) return r;
  Engine engine(sys, plan, options);
  Result res = run_steps(sys, set, plan, engine);
  if (paths_out) *paths_out = engine.paths();
  return res;
}

}  // namespace pb::siconos
