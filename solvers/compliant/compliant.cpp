#include "solvers/compliant/compliant.hpp"

#include <cmath>
#include <exception>

#include "cases/text.hpp"
#include "solvers/compliant/integrators.hpp"
#include "kit/contact_elements/contact_law.hpp"
#include "kit/fixed_step.hpp"
#include "kit/named_values.hpp"

namespace pb::compliant {

namespace {

bool is_newmark(const Settings& s) { return s.integrator == "newmark"; }
bool is_adams(const Settings& s) { return s.method == "adams"; }
double stiffness(const Settings& s) { return s.stiffness > 0.0 ? s.stiffness : kDefaultStiffness; }

}  // namespace

std::vector<VariantInfo> variant_list() {
  std::vector<VariantInfo> out;
  for (Model m : kModels) out.push_back({name(m), std::string(summary(m))});
  return out;
}

std::string check(const Settings& settings) {
  if (!parse_model(settings.variant)) {
    std::string known;
    for (Model m : kModels) known += (known.empty() ? "" : ", ") + std::string(name(m));
    return "variant: unknown '" + settings.variant + "' (known: " + known + ")";
  }
  if (!(settings.stiffness >= 0.0) || !std::isfinite(settings.stiffness))
    return "stiffness: must be finite and > 0 (0: the default " + format_number(kDefaultStiffness) + ")";
  if (!settings.integrator.empty() && settings.integrator != "cvode" && settings.integrator != "newmark")
    return "integrator: unknown '" + settings.integrator + "' (known: cvode, newmark)";
  if (!settings.method.empty() && settings.method != "bdf" && settings.method != "adams")
    return "method: unknown '" + settings.method + "' (known: bdf, adams)";
  if (is_newmark(settings)) {
    if (!settings.method.empty()) return "method: only the cvode integrator has one";
    if (settings.rtol != 0.0) return "rtol: the newmark integrator takes a fixed step (--steps or --wh)";
    return check_step(settings, kDefaultSteps);
  }
  if (!(settings.rtol >= 0.0 && settings.rtol < 1.0)) return "rtol: must be in (0, 1) (0: the default 1e-8)";
  if (settings.rtol > 0.0 && settings.rtol < 1e-14) return "rtol: below 1e-14 is below double precision's round-off";
  if (settings.steps != 0) return "steps: the cvode integrator chooses its own steps (--rtol)";
  if (settings.wh != 0.0) return "wh: the cvode integrator chooses its own steps (--rtol)";
  return {};
}

Result solve(const System& system, const Settings& settings) {
  if (std::string bad = check(settings); !bad.empty()) return failed(bad);
  const Model model = *parse_model(settings.variant);
  if (std::string_view bad = eps_problem(model, system.eps); !bad.empty())
    return failed("eps: " + std::string(bad));
  if (model != Model::kelvin_voigt && !(system.contact_length_scale() > 0.0))
    return failed("record: its Fourier amplitudes vanish between 0.25 and 20 Hz, so it has no mean period to "
                  "give a Hertz-type element its length scale (cases/README.md)");
  for (const Body& b : system.bodies)
    if (!(b.m > 0.0 && std::isfinite(b.m) && std::isfinite(b.k) && std::isfinite(b.c)))
      return failed("every body needs a finite positive mass and a finite spring and dashpot");
  try {
    return is_newmark(settings) ? run_newmark(system, settings, model, stiffness(settings))
                                : run_cvode(system, settings, model, stiffness(settings), is_adams(settings));
  } catch (const std::exception& e) {
    return failed(e.what());
  }
}

bool hertz_contact(const Settings& settings) {
  const auto model = parse_model(settings.variant);
  return model && *model != Model::kelvin_voigt;
}

std::optional<ModelReference> model_reference(const Settings& settings) {
  const auto model = parse_model(settings.variant);
  if (!model) return std::nullopt;
  ModelReference ref{"", {}};
  ref.settings.stiffness = settings.stiffness;
  ref.settings.k_contact = settings.k_contact;
  ref.settings.time_limit = settings.time_limit;
  ref.settings.point_time_limit = settings.point_time_limit;
  if (*model == Model::kelvin_voigt) {
    ref.solver = "event-driven";
    ref.settings.contact = "kelvin-voigt";
    return ref;
  }
  if (!is_newmark(settings) && !is_adams(settings) && settings.rtol == kModelReferenceRtol) return std::nullopt;
  ref.solver = "compliant";
  ref.settings.variant = name(*model);
  ref.settings.rtol = kModelReferenceRtol;
  return ref;
}

std::string describe(const Settings& settings) {
  NamedValues out;
  const auto model = parse_model(settings.variant);
  out.add("variant", model ? name(*model) : std::string_view(settings.variant));
  add_stiffness(out, settings, stiffness(settings));
  if (is_newmark(settings)) {
    out.add("integrator", "newmark");
    add_step(out, settings, kDefaultSteps);
  } else {
    // The names as given (a row records what was asked, as for an unknown variant).
    out.add("integrator", settings.integrator.empty() ? "cvode" : std::string_view(settings.integrator));
    out.add("method", settings.method.empty() ? "bdf" : std::string_view(settings.method));
    out.add("rtol", settings.rtol > 0.0 ? settings.rtol : kDefaultRtol);
  }
  return out.json();
}

}  // namespace pb::compliant
