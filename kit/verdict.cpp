#include "kit/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pb {

namespace {

// Three significant digits: a reason to read (the row's columns hold every digit).
std::string brief(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

}  // namespace

std::string percent(double relative) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g %%", 100.0 * relative);
  return text;
}

void judge(const System& system, Result& r, const VerdictScope& scope) {
  r.resolved.reset();
  r.unresolved.clear();
  if (r.status != Status::ok) return;
  std::string why;
  const auto fail = [&why](const std::string& reason) { why += (why.empty() ? "" : "; ") + reason; };
  if (const double per_period = system.t_min / r.step; per_period < kMinStepsPerPeriod)
    fail("its step is " + brief(1.0 / per_period) + " of the shortest period T_min (fewer than " +
         brief(kMinStepsPerPeriod) + " steps a period)");
  if (r.contact_steps_min < kMinContactSteps)
    fail("a contact lasted " + brief(r.contact_steps_min) + " step ends of the integrator (fewer than " +
         brief(kMinContactSteps) + ")");
  if (r.energy_excess > kEnergyMade)
    fail("it made energy, " + brief(r.energy_excess) + " of the energy scale (above " +
         brief(kEnergyMade) + ")");
  if (r.isolated_impacts > 0 && !r.restitution_over_contacts) {
    const double off = std::max(std::abs(r.restitution_low - system.eps), std::abs(r.restitution_high - system.eps));
    if (off > kRestitutionMargin)
      fail("its isolated impacts restituted " + brief(r.restitution_low) + " to " +
           brief(r.restitution_high) + " for eps " + brief(system.eps) + " (off by more than " +
           brief(kRestitutionMargin) + ")");
  }
  if (r.error_estimate > scope.target_error)
    fail("error estimate " + percent(r.error_estimate) + " > target " + percent(scope.target_error) +
         " (its Pi1 against a companion solve at twice the step)");
  if (r.error_estimate_velocity > scope.target_error)
    fail("impact velocity error estimate " + percent(r.error_estimate_velocity) + " > target " +
         percent(scope.target_error) + " (its fastest approach against the companion's: its impacts have not converged)");
  if (!r.doubt.empty()) fail(r.doubt);
  if (why.empty() && !scope.complete) return;  // not judged: what was not measured could fail
  r.resolved = why.empty();
  r.unresolved = std::move(why);
}

}  // namespace pb
