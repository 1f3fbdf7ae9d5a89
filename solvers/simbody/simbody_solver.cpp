#include "solvers/simbody/simbody_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <optional>
#include <sstream>

#include "cases/text.hpp"
#include "kit/contact_elements/contact_law.hpp"
#include "kit/fixed_step.hpp"
#include "kit/run_limits.hpp"
#include "solvers/simbody/model.hpp"
#include "solvers/simbody/variants.hpp"
#include "kit/variant_table.hpp"
#include "kit/whole_contacts.hpp"

namespace pb::simbody {

namespace {

// The model's units: the pulse's length a_p / w_p^2, time 1 / w_p, and body 0's mass.
struct Units {
  double length, time, mass;
  explicit Units(const System& sys) : length(sys.length_scale()), time(1.0 / sys.pulse.w), mass(sys.bodies[ix(sys.ref)].m) {}
  double velocity() const { return length / time; }
  double force() const { return mass * length / (time * time); }
};

ModelSpec model_spec(const System& sys, const Config& config, const Settings& set, double h, const Units& units) {
  ModelSpec spec;
  spec.kind = config.kind;
  for (int i = 0; i < sys.n_bodies(); ++i) {
    const Body& b = sys.bodies[ix(i)];
    spec.m.push_back(b.m / units.mass);
    spec.k.push_back(b.k * units.time * units.time / units.mass);
    spec.c.push_back(b.c * units.time / units.mass);
  }
  for (const double u : start_u(sys)) spec.u.push_back(u / units.length);
  for (const double v : start_v(sys)) spec.v.push_back(v / units.velocity());
  for (int j = 0; j < sys.n_contacts(); ++j) {
    spec.left.push_back(sys.left(j) == kWall ? -1 : sys.left(j));
    spec.right.push_back(sys.right(j));
  }
  spec.delta = sys.delta / units.length;
  spec.eps = sys.eps;
  spec.ground_accel = [load = LoadCursor(sys.pulse), units](double t) mutable {
    return load.accel(t * units.time) * units.time * units.time / units.length;
  };
  spec.h = h / units.time;
  spec.gamma = set.gamma;
  spec.constraint_tol = kFaithfulConstraintTol;
  if (config.kind == Kind::hunt_crossley) {
    const double w0 = sys.bodies[ix(sys.ref)].w * units.time;
    spec.hertz = stiffness(set) * w0 * w0;  // K m0 w0^2 / sqrt(a_p / w_p^2), in the model's units
    spec.dissipation = compliant::hunt_crossley_chi(sys.eps) / (1.5 * kCalibrationSpeed);
    spec.accuracy = accuracy(set);
  }
  return spec;
}

// The extreme of the cubic Hermite interpolant of x over [t0, t1] (values x0, x1, slopes v0,
// v1 of opposite signs), where x' = 0 between the two: the peak an integrator's step passes.
double hermite_extreme(double t0, double x0, double v0, double t1, double x1, double v1) {
  const double h = t1 - t0, m0 = h * v0, m1 = h * v1;
  // x'(s) h = a s^2 + b s + c on s in [0, 1]
  const double a = 6.0 * x0 + 3.0 * m0 - 6.0 * x1 + 3.0 * m1, b = -6.0 * x0 - 4.0 * m0 + 6.0 * x1 - 2.0 * m1, c = m0;
  double s = -c / b;
  if (std::abs(a) > 1e-12 * (std::abs(b) + std::abs(c))) {
    const double d = std::sqrt(std::max(0.0, b * b - 4.0 * a * c));
    const double q = -0.5 * (b + std::copysign(d, b));
    const double r1 = q / a, r2 = c / q;
    s = (r1 >= 0.0 && r1 <= 1.0) ? r1 : r2;
  }
  s = std::clamp(s, 0.0, 1.0);
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * x1 + (s3 - s2) * m1;
}

// x to two significant digits, for a message ("12 s", "0.037 s").
std::string two_digits(double x) {
  std::ostringstream out;
  out.precision(2);
  out << x;
  return out.str();
}

// How far a run may pass its time limit inside a step that cannot be interrupted: a tenth of
// the limit, and half a second at least. A step of PLUS whose silent stretches
// (Model::silent_seconds) could pass it is not started (Engine::too_silent).
constexpr double kLimitMargin = 0.1, kLimitMarginMin = 0.5;
// The silent stretches a stepper's step can hold: after the limit passes inside one, the
// impulse solves still to come (an impact's compression and reaction rounds, the dynamics
// phase, the default variant's position projection) each run one more before they stop.
constexpr int kSilentPerStep = 4;

// Simbody behind the shared step loop (kit/fixed_step.hpp). The run's limit is its
// deadline, started before the model was built and asked inside each step too (ModelSpec::
// out_of_time): a step of a 1000-body chain took minutes (PLUS on 999 contacts).
class Engine : public StepEngine {
 public:
  Engine(const System& sys, const Config& config, ModelSpec spec, const Units& units, const Settings& set, double h,
         Deadline& deadline)
      : StepEngine(sys), sys_(sys), compliant_(!config.time_stepper()), units_(units), h_(h),
        limit_(set.time_limit), start_(std::chrono::steady_clock::now()), deadline_(deadline),
        model_(with_deadline(std::move(spec), deadline)), engaged_(ix(sys.n_contacts()), 0), whole_(sys), u_(out_.u),
        v_(out_.v), v_before_(out_.v), touching_(ix(sys.n_contacts()), 0) {
    if (compliant_) inner_step(0.0, out_.u, out_.v);
  }

  StepOutcome step(long k, Result& res) override {
    if (deadline_.tick()) return out_of_time(k, "", res);
    if (too_silent(k, res)) return StepOutcome::refused;
    bool done = true;
    try {
      if (compliant_)
        done = model_.step(k, [this](double t, const double* q, const double* u) { inner_step(t, q, u); });
      else
        done = model_.step(k);
    } catch (const std::exception& e) {
      res.status = Status::failed;
      res.message = e.what() + std::string(" (step ") + std::to_string(k + 1) + ")";
      return StepOutcome::refused;
    }
    if (!done) return out_of_time(k, ", inside Simbody's step " + std::to_string(k + 1), res);
    for (int i = 0; i < sys_.n_bodies(); ++i) {
      out_.u[ix(i)] = model_.u(i) * units_.length;
      out_.v[ix(i)] = model_.v(i) * units_.velocity();
    }
    for (int j = 0; j < sys_.n_contacts(); ++j) {
      const auto jj = ix(j);
      const ContactStep& c = model_.contact(j);
      out_.force[jj] = c.force * units_.force();
      out_.entered[jj] = c.engaged && !engaged_[jj] ? 1 : 0;
      engaged_[jj] = c.engaged ? 1 : 0;
    }
    return StepOutcome::taken;
  }

  void finish(Result& res) override {
    if (!compliant_) return;
    whole_.finish(res);
    // The peak between reports, which the integrator's own steps resolve (its time: the end
    // of the internal step that passed it).
    if (res.status == Status::ok) {
      res.pi1 = sys_.pi1(u0_max_);
      res.t_max = t_max_;
    }
  }

 private:
  // hunt-crossley, after each internal step of the integrator (t and the state in the
  // model's units): the largest |u0| and the whole contacts, an element acting over the
  // internal step if it penetrates at either end of it.
  template <class Values>
  void inner_step(double t, const Values& q, const Values& u) {
    for (int i = 0; i < sys_.n_bodies(); ++i) {
      u_[ix(i)] = q[ix(i)] * units_.length;
      v_[ix(i)] = u[ix(i)] * units_.velocity();
    }
    const auto r = ix(sys_.ref);
    const double time = t * units_.time;
    double peak = u_[r];
    if (v_[r] * v_before_[r] < 0.0) peak = hermite_extreme(t_before_, u_before_, v_before_[r], time, u_[r], v_[r]);
    if (std::abs(peak) > u0_max_) {
      u0_max_ = std::abs(peak);
      t_max_ = time;
    }
    t_before_ = time;
    u_before_ = u_[r];
    for (int j = 0; j < sys_.n_contacts(); ++j) {
      const char now = sys_.gap(j, u_.data()) < 0.0 ? 1 : 0;
      whole_.step(j, now || touching_[ix(j)], v_before_.data());
      touching_[ix(j)] = now;
    }
    v_before_ = v_;
  }

  static ModelSpec with_deadline(ModelSpec spec, Deadline& deadline) {
    spec.out_of_time = [&deadline] { return deadline.tick(); };
    return spec;
  }

  StepOutcome out_of_time(long k, const std::string& where, Result& res) const {
    res.status = Status::time_limit;
    res.message = deadline_.reason() + " at t = " + std::to_string(static_cast<double>(k) * h_) + where;
    return StepOutcome::refused;
  }

  // True (res says why) where the next step's impulse solve could pass the limit by more than
  // its margin without a look at the clock.
  bool too_silent(long k, Result& res) {
    if (!(limit_ > 0.0) || compliant_) return false;
    const int contacts = model_.contacts_next_step();
    const double silent = model_.silent_seconds(contacts);
    const double margin = std::max(kLimitMarginMin, kLimitMargin * limit_);
    if (!(kSilentPerStep * silent > margin)) return false;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    res.status = Status::time_limit;
    res.message = "refused at t = " + format_number(static_cast<double>(k) * h_) + " after " + two_digits(elapsed) +
                  " s: the next step's impulse solve (Simbody's PLUS, " + std::to_string(contacts) +
                  " contacts) runs about " + two_digits(silent) +
                  " s at a time where no limit can stop it (Debian's build checks every Newton iteration's "
                  "Jacobian numerically), up to " + std::to_string(kSilentPerStep) +
                  " times in a step: more than the limit's margin of " + two_digits(margin) + " s";
    return true;
  }

  const System& sys_;
  bool compliant_;
  Units units_;
  double h_;                                       // the step (hunt-crossley: the report interval)
  double limit_;                                   // Settings::time_limit
  std::chrono::steady_clock::time_point start_;    // the model's set-up
  Deadline& deadline_;
  Model model_;
  std::vector<char> engaged_;  // per contact, in the last step
  // hunt-crossley: whole contacts and the peak over the integrator's internal steps
  WholeContacts whole_;
  std::vector<double> u_, v_, v_before_;  // at the last internal step, and the one before
  std::vector<char> touching_;            // per contact, at the last internal step
  double u0_max_ = 0.0, t_max_ = 0.0;
  double t_before_ = 0.0, u_before_ = 0.0;  // body 0 at the internal step before
};

Result run(const System& sys, const Settings& set, const Config& config) {
  for (const Body& b : sys.bodies)
    if (!(b.m > 0.0 && std::isfinite(b.m)) || !std::isfinite(b.k) || !std::isfinite(b.c))
      return failed("every body needs a finite positive mass and a finite stiffness and damping");
  Settings stepping = set;
  if (config.kind == Kind::hunt_crossley) {
    if (std::string_view bad = compliant::eps_problem(compliant::Model::hunt_crossley, sys.eps); !bad.empty())
      return failed("eps: " + std::string(bad));
    stepping.steps = kHuntCrossleyReports;
  }
  StepPlan plan;
  if (Result r = plan_steps(sys, stepping, kDefaultSteps, kDefaultStepCap, plan); r.status != Status::ok) return r;
  const Units units(sys);
  Deadline deadline(set);  // from here: the model's set-up counts against the limit
  Engine engine(sys, config, model_spec(sys, config, set, plan.h, units), units, set, plan.h, deadline);
  return run_steps(sys, set, plan, engine);
}

}  // namespace

Result solve(const System& system, const Settings& settings) {
  return solve_linear_variant(kVariants, system, settings,
                              "simbody's MobilityLinearSpring is linear; the bilinear law is not applied (moreau-jean, "
                              "ode and bullet apply it)",
                              &run);
}

std::string describe(const Settings& settings) {
  return describe_variant(kVariants, settings, kDefaultSteps);
}

std::string check(const Settings& settings) {
  const std::optional<Config> config = kVariants.find(settings.variant);
  if (std::string bad = check_variant("simbody", kVariants, settings, kDefaultSteps); !bad.empty()) return bad;
  if (!config->time_stepper()) {
    if (settings.steps != 0) return "steps: hunt-crossley's integrator chooses its own steps (--rtol)";
    if (settings.wh != 0.0) return "wh: hunt-crossley's integrator chooses its own steps (--rtol)";
    if (!(settings.stiffness >= 0.0) || !std::isfinite(settings.stiffness))
      return "stiffness: must be finite and > 0 (0: the default " + format_number(kDefaultStiffness) + ")";
    if (!(settings.rtol >= 0.0 && settings.rtol < 1.0)) return "rtol: must be in (0, 1) (0: the default " + format_number(kDefaultAccuracy) + ")";
    if (settings.rtol > 0.0 && settings.rtol < 1e-14) return "rtol: below 1e-14 is below double precision's round-off";
  }
  return {};
}

}  // namespace pb::simbody
