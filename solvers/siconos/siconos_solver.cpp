#include "solvers/siconos/siconos_solver.hpp"

#include <array>
#include <cmath>
#include <exception>

#include "solvers/siconos/model.hpp"

namespace pb::siconos {

namespace {

enum class Scheme { time_stepping, event_driven, newmark_alpha };
using engine::Integrator;

// Which LCP solver a variant uses: the one its name says, or Settings::lcp.
enum class Lcp { lemke, enumeration, setting };

struct Variant {
  std::string_view name;
  Scheme scheme;
  Integrator integrator;
  Lcp lcp;
  std::string_view summary;
};

constexpr std::array kVariants = {
    Variant{"moreau-jean-lemke", Scheme::time_stepping, Integrator::moreau_jean, Lcp::lemke,
            "TimeStepping with MoreauJeanOSI, its LCP by Lemke"},
    Variant{"moreau-jean-enum", Scheme::time_stepping, Integrator::moreau_jean, Lcp::enumeration,
            "TimeStepping with MoreauJeanOSI, its LCP by enumeration"},
    Variant{"event-driven-lsodar", Scheme::event_driven, Integrator::moreau_jean, Lcp::lemke,
            "EventDriven with LsodarOSI; fails where contact persists"},
    Variant{"schatzman-paoli", Scheme::time_stepping, Integrator::schatzman_paoli, Lcp::setting,
            "TimeStepping with SchatzmanPaoliOSI: Newton's law at the position level, every contact in its LCP"},
    Variant{"d1-minus-linear", Scheme::time_stepping, Integrator::d1_minus_linear, Lcp::setting,
            "TimeSteppingD1Minus with D1MinusLinearOSI: half-explicit at the acceleration level, impact and force LCPs"},
    Variant{"combined-projection", Scheme::time_stepping, Integrator::combined_projection, Lcp::setting,
            "TimeSteppingCombinedProjection: MoreauJeanOSI's step, then the positions projected onto the gaps (MLCP)"},
    Variant{"direct-projection", Scheme::time_stepping, Integrator::direct_projection, Lcp::setting,
            "TimeSteppingDirectProjection: MoreauJeanOSI's step, then a direct projection of the positions (MLCP)"},
    Variant{"bilbao", Scheme::time_stepping, Integrator::bilbao, Lcp::setting,
            "MoreauJeanBilbaoOSI (Bilbao's scheme for linear oscillators); fails: its free state leaves out the ground load"},
    Variant{"newmark-alpha", Scheme::newmark_alpha, Integrator::moreau_jean, Lcp::lemke,
            "EventDriven with NewMarkAlphaOSI; fails: its computeW negates the system's K and C in place"},
};

const Variant* find_variant(std::string_view name) {
  if (name.empty()) name = kDefaultVariant;
  for (const Variant& v : kVariants)
    if (v.name == name) return &v;
  return nullptr;
}

bool enumeration(const Variant& v, const Settings& settings) {
  return v.lcp == Lcp::enumeration || (v.lcp == Lcp::setting && settings.lcp == "enum");
}

bool projects(const Variant& v) {
  return v.integrator == Integrator::combined_projection || v.integrator == Integrator::direct_projection;
}

// theta, and gamma where the integrator takes it (MoreauJeanOSI's activation rule).
bool takes_theta(const Variant& v) {
  return v.scheme == Scheme::time_stepping && v.integrator != Integrator::d1_minus_linear &&
         v.integrator != Integrator::bilbao;
}
bool takes_gamma(const Variant& v) {
  return v.scheme == Scheme::time_stepping &&
         (v.integrator == Integrator::moreau_jean || v.integrator == Integrator::direct_projection);
}

double projection_tol(const Settings& settings) {
  return settings.projection_tol > 0.0 ? settings.projection_tol : kProjectionTol;
}

engine::StepperOptions stepper_options(const Variant& v, const Settings& settings) {
  engine::StepperOptions o;
  o.integrator = v.integrator;
  o.theta = settings.theta;
  o.gamma = settings.gamma;
  o.enumeration = enumeration(v, settings);
  o.projection_tol = projection_tol(settings);
  o.projection_iterations = kProjectionIterations;
  return o;
}

// The run of a variant; a Siconos exception that escapes it ends the run as failed.
Result run(const Variant& variant, const System& system, const Settings& settings, LcpPaths* paths) {
  // moreau-jean-enum keeps its behaviour of before: its LCP driver reaches enumeration only
  // with several contacts active at once and one to push.
  const bool enumerates = projects(variant) || (variant.lcp == Lcp::setting && enumeration(variant, settings));
  if (enumerates && system.n_contacts() > kMaxEnumerationContacts)
    return stopped(Status::failed, std::string(variant.name) + ": its " +
                                       (projects(variant) ? "projection's MLCP" : "LCP") +
                                       " by enumeration tries up to 2^n active sets, n = " +
                                       std::to_string(system.n_contacts()) + " contacts here; it takes up to " +
                                       std::to_string(kMaxEnumerationContacts) + " (a larger one may never end)");
  try {
    switch (variant.scheme) {
      case Scheme::event_driven: return run_event_driven(system, settings);
      case Scheme::newmark_alpha: return run_newmark_alpha(system, settings);
      case Scheme::time_stepping: break;
    }
    return run_time_stepping(system, settings, stepper_options(variant, settings), paths);
  } catch (const std::exception& e) {
    return stopped(Status::failed, std::string("Siconos: ") + e.what());
  }
}

}  // namespace

Result solve(const System& system, const Settings& settings) {
  const Variant* variant = find_variant(settings.variant);
  if (!variant) return stopped(Status::failed, "unknown variant " + settings.variant);
  if (system.yields())
    return yielding_refused("siconos' LagrangianLinearTIDS owns the bodies' springs (its constant K); "
                            "the bilinear law is not applied");
  return run(*variant, system, settings, nullptr);
}

Result solve_counting(const System& system, const Settings& settings, LcpPaths& paths) {
  paths = {};
  const Variant* variant = find_variant(settings.variant);
  if (!variant || variant->scheme != Scheme::time_stepping || variant->integrator != Integrator::moreau_jean)
    return stopped(Status::failed, "solve_counting: a MoreauJeanOSI variant only");
  return run(*variant, system, settings, &paths);
}

MoreauJeanSetup moreau_jean_setup(const System& system, const Settings& settings) {
  const Variant* variant = find_variant(settings.variant);
  const double h = time_step(system, settings, kDefaultSteps);
  const engine::TimeStepper run(model_spec(system, h, system.t_end + h), h / units_of(system).time,
                                stepper_options(variant ? *variant : kVariants[0], settings));
  return {run.theta(), run.gamma(), run.uses_gamma(), run.activation_threshold()};
}

std::string describe(const Settings& settings) {
  const Variant* variant = find_variant(settings.variant);
  NamedValues out;
  if (!variant) return out.add("variant", settings.variant).json();
  if (variant->scheme == Scheme::event_driven) {
    out.add("tol_scale", settings.tol_scale).add("rtol", kRtol * settings.tol_scale);
    out.add("atol", kAtol * settings.tol_scale).add("output", "T_min/" + std::to_string(kOutputSteps));
    return out.json();
  }
  add_step(out, settings, kDefaultSteps);
  if (variant->scheme == Scheme::newmark_alpha) {
    out.add("rho_infty", kRhoInfinity).add("lcp", "lemke");
    return out.json();
  }
  if (takes_theta(*variant)) out.add("theta", settings.theta);
  if (takes_gamma(*variant)) out.add("gamma", settings.gamma);
  if (variant->lcp == Lcp::setting)
    out.add("lcp", settings.lcp.empty() ? std::string("lemke") : settings.lcp);
  else
    out.add("lcp", enumeration(*variant, settings) ? "enum" : "lemke");
  if (projects(*variant)) {
    out.add("mlcp", "enum").add("projection_tol", projection_tol(settings));
    out.add("projection_iterations", kProjectionIterations);
  }
  return out.json();
}

std::vector<VariantInfo> variant_list() {
  std::vector<VariantInfo> out;
  for (const Variant& v : kVariants) out.push_back({v.name, std::string(v.summary)});
  return out;
}

std::string check(const Settings& settings) {
  const Variant* variant = find_variant(settings.variant);
  if (!variant) {
    std::string known;
    for (const Variant& v : kVariants) known += (known.empty() ? "" : ", ") + std::string(v.name);
    return "variant: unknown '" + settings.variant + "' (known: " + known + ")";
  }
  const std::string name(variant->name);
  if (variant->scheme == Scheme::event_driven) {
    if (settings.steps != 0 || settings.wh != 0.0)
      return "steps: event-driven-lsodar has no fixed step (tol_scale sets its tolerances)";
    if (!(settings.tol_scale > 0.0) || !std::isfinite(settings.tol_scale)) return "tol_scale: must be finite and > 0";
  } else {
    if (std::string step = check_step(settings, kDefaultSteps); !step.empty()) return step;
    if (takes_theta(*variant))
      if (std::string theta = check_theta_method(settings); !theta.empty()) return theta;
  }
  if (variant->lcp == Lcp::setting) {
    if (!settings.lcp.empty() && settings.lcp != "lemke" && settings.lcp != "enum")
      return "lcp: must be lemke or enum, not '" + settings.lcp + "'";
  } else if (!settings.lcp.empty() && settings.lcp != (variant->lcp == Lcp::enumeration ? "enum" : "lemke")) {
    return "lcp: " + name + " names its LCP solver (" + (variant->lcp == Lcp::enumeration ? "enum" : "lemke") +
           "); choose it by the variant";
  }
  if (!(settings.projection_tol >= 0.0) || !std::isfinite(settings.projection_tol))
    return "projection_tol: must be finite and >= 0 (0: the default, 1e-10)";
  if (settings.projection_tol != 0.0 && !projects(*variant))
    return "projection_tol: " + name + " does not project (combined-projection and direct-projection do)";
  return {};
}

}  // namespace pb::siconos
