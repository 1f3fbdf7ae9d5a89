#include "solvers/penalty_verlet/penalty_verlet.hpp"

#include <cmath>
#include <cstddef>

#include "kit/contact_elements/contact_law.hpp"
#include "kit/fixed_step.hpp"
#include "kit/named_values.hpp"
#include "kit/whole_contacts.hpp"

namespace pb::penalty_verlet {

namespace {

std::size_t ix(int i) { return static_cast<std::size_t>(i); }

// Its element is stiff: its contact lasts pi sqrt(m_eff / k), which the step must resolve
// (the verdict's compliant-contact criterion, kit/verdict.hpp, says when it does not).
double stiffness_term(const Settings& s) { return s.stiffness > 0.0 ? s.stiffness : compliant::kDefaultStiffness; }

// A step of velocity Verlet (kick, drift, kick) with every force at the state it acts in: the
// springs, dampers, the load, and each closed contact's Kelvin-Voigt element.
class Engine final : public StepEngine {
 public:
  Engine(const System& sys, const Settings& set, double h)
      : StepEngine(sys), sys_(sys), h_(h), contacts_(sys), a_(ix(sys.n_bodies())), touched_(ix(sys.n_contacts()), 0) {
    const double k = stiffness_term(set) * sys.bodies[ix(sys.ref)].k;  // k = K m0 w0^2
    for (int j = 0; j < sys.n_contacts(); ++j) {
      const int l = sys.left(j);
      laws_.push_back(compliant::make_law(compliant::Model::kelvin_voigt, k, sys.eps,
                                          l == kWall ? 0.0 : sys.bodies[ix(l)].m, sys.bodies[ix(sys.right(j))].m));
    }
    accelerations(0.0);
  }

  StepOutcome step(long k, Result&) override {
    std::vector<double>& u = out_.u;
    std::vector<double>& v = out_.v;
    for (int j = 0; j < sys_.n_contacts(); ++j) {
      const bool touched = sys_.gap(j, u.data()) < 0.0;
      contacts_.step(j, touched, v.data());  // the velocities at the step's start
      out_.entered[ix(j)] = touched && !touched_[ix(j)] ? 1 : 0;
      touched_[ix(j)] = touched;
    }
    for (int i = 0; i < sys_.n_bodies(); ++i) {
      v[ix(i)] += 0.5 * h_ * a_[ix(i)];
      u[ix(i)] += h_ * v[ix(i)];
    }
    accelerations(static_cast<double>(k + 1) * h_);
    for (int i = 0; i < sys_.n_bodies(); ++i) v[ix(i)] += 0.5 * h_ * a_[ix(i)];
    return StepOutcome::taken;
  }

  void finish(Result& res) override { contacts_.finish(res); }
  bool contacts_have_duration() const override { return true; }

 private:
  // a = M^-1 (-C v - K u + contact forces) - a_g(t), and each contact's force into out().
  void accelerations(double t) {
    const std::vector<double>& u = out_.u;
    const std::vector<double>& v = out_.v;
    const double a_g = sys_.pulse.accel(t);
    for (int i = 0; i < sys_.n_bodies(); ++i) {
      const Body& b = sys_.bodies[ix(i)];
      a_[ix(i)] = -(b.c * v[ix(i)] + b.k * u[ix(i)]) / b.m - a_g;
    }
    for (int j = 0; j < sys_.n_contacts(); ++j) {
      const double g = sys_.gap(j, u.data());
      const double f = g < 0.0 ? laws_[ix(j)].force(-g, -sys_.gap_rate(j, v.data()), 0.0) : 0.0;
      out_.force[ix(j)] = f;
      const int l = sys_.left(j), r = sys_.right(j);
      a_[ix(r)] += f / sys_.bodies[ix(r)].m;
      if (l != kWall) a_[ix(l)] -= f / sys_.bodies[ix(l)].m;
    }
  }

  const System& sys_;
  double h_;
  WholeContacts contacts_;
  std::vector<compliant::Law> laws_;
  std::vector<double> a_;       // accelerations at the step's end, the next step's start
  std::vector<char> touched_;  // per contact: closed at the last step's start
};

}  // namespace

Result solve(const System& system, const Settings& settings) {
  if (std::string bad = check(settings); !bad.empty()) return failed(bad);
  if (system.yields()) return yielding_refused("this example integrates linear springs only");
  StepPlan plan;
  if (Result r = plan_steps(system, settings, kDefaultSteps, kDefaultStepCap, plan); r.status != Status::ok) return r;
  Engine engine(system, settings, plan.h);
  return run_steps(system, settings, plan, engine);
}

std::string describe(const Settings& settings) {
  NamedValues out;
  add_step(out, settings, kDefaultSteps);
  out.add("stiffness", stiffness_term(settings));
  return out.json();
}

std::string check(const Settings& settings) {
  if (!settings.variant.empty() && settings.variant != "kelvin-voigt")
    return "variant: unknown '" + settings.variant + "' (known: kelvin-voigt)";
  if (std::string bad = check_step(settings, kDefaultSteps); !bad.empty()) return bad;
  if (!(settings.stiffness >= 0.0 && std::isfinite(settings.stiffness)))
    return "stiffness: must be a finite number >= 0 (0: the default)";
  return {};
}

std::vector<VariantInfo> variant_list() {
  return {{"kelvin-voigt", "velocity Verlet, a Kelvin-Voigt element on each closed contact"}};
}

}  // namespace pb::penalty_verlet
