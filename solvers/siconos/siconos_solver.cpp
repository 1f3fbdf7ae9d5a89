#include "solvers/siconos/siconos_solver.hpp"

#include <array>
#include <cmath>
#include <exception>

#include "solvers/siconos/model.hpp"

namespace pb::siconos {

namespace {

enum class Scheme { time_stepping, event_driven };

struct Variant {
  std::string_view name;
  Scheme scheme;
  bool enumeration;  // time-stepping: the LCP by enumeration instead of Lemke
  std::string_view summary;
};

constexpr std::array kVariants = {
    Variant{"moreau-jean-lemke", Scheme::time_stepping, false, "TimeStepping with MoreauJeanOSI, its LCP by Lemke"},
    Variant{"moreau-jean-enum", Scheme::time_stepping, true, "TimeStepping with MoreauJeanOSI, its LCP by enumeration"},
    Variant{"event-driven-lsodar", Scheme::event_driven, false,
            "EventDriven with LsodarOSI; fails where contact persists"},
};

const Variant* find_variant(std::string_view name) {
  if (name.empty()) name = kDefaultVariant;
  for (const Variant& v : kVariants)
    if (v.name == name) return &v;
  return nullptr;
}

// The run of a variant; a Siconos exception that escapes it ends the run as failed.
Result run(const Variant& variant, const System& system, const Settings& settings, LcpPaths* paths) {
  try {
    if (variant.scheme == Scheme::event_driven) return run_event_driven(system, settings);
    return run_time_stepping(system, settings, variant.enumeration, paths);
  } catch (const std::exception& e) {
    return stopped(Status::failed, std::string("Siconos: ") + e.what());
  }
}

}  // namespace

Result solve(const System& system, const Settings& settings) {
  const Variant* variant = find_variant(settings.variant);
  if (!variant) return stopped(Status::failed, "unknown variant " + settings.variant);
  return run(*variant, system, settings, nullptr);
}

Result solve_counting(const System& system, const Settings& settings, LcpPaths& paths) {
  paths = {};
  const Variant* variant = find_variant(settings.variant);
  if (!variant || variant->scheme != Scheme::time_stepping)
    return stopped(Status::failed, "solve_counting: a time-stepping variant only");
  return run(*variant, system, settings, &paths);
}

MoreauJeanSetup moreau_jean_setup(const System& system, const Settings& settings) {
  const Variant* variant = find_variant(settings.variant);
  const double h = time_step(system, settings, kDefaultSteps);
  const engine::TimeStepper run(model_spec(system, h, system.t_end + h), h / units_of(system).time, settings.theta,
                                settings.gamma, variant && variant->enumeration);
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
  out.add("theta", settings.theta).add("gamma", settings.gamma).add("lcp", variant->enumeration ? "enum" : "lemke");
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
  if (variant->scheme == Scheme::event_driven) {
    if (settings.steps != 0 || settings.wh != 0.0)
      return "steps: event-driven-lsodar has no fixed step (tol_scale sets its tolerances)";
    if (!(settings.tol_scale > 0.0) || !std::isfinite(settings.tol_scale)) return "tol_scale: must be finite and > 0";
  } else {
    if (std::string step = check_step(settings, kDefaultSteps); !step.empty()) return step;
    if (std::string theta = check_theta_method(settings); !theta.empty()) return theta;
  }
  return check_limits(settings);
}

}  // namespace pb::siconos
