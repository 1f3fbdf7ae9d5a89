#include "cases/physical.hpp"

#include <algorithm>
#include <cstdio>
#include <numbers>

#include "cases/record.hpp"
#include "cases/system.hpp"

namespace pb {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

bool given(double x) { return !std::isnan(x); }

// A value or a bound as a message shows it: "1e-30", "inf", "6.28319e+308".
std::string value_text(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

}  // namespace

bool used_by(const PhysicalField& field, Scene scene) {
  return scene_uses(field.use, scene);
}

bool physical(const Case& c) {
  for (const PhysicalField& f : kPhysicalFields)
    if (given(c.physical.*f.member)) return true;
  return false;
}

bool physical_value_ok(const PhysicalField& field, double x) {
  // The gap may be 0 (bodies touching at rest, Pi3 = 0); periods and masses may not; a
  // yield displacement may be inf (elastic), as its Pi term.
  if (field.pi.starts_with("pi_y")) return x > 0.0;
  if (field.name == "gap") return std::isfinite(x) && x >= 0.0;
  if (field.name.starts_with("m")) return x >= kMinMass && x <= kMaxMass;
  return std::isfinite(x) && x > 0.0;
}

std::string physical_rule(const PhysicalField& field) {
  if (field.pi.starts_with("pi_y")) return "must be > 0 (inf: elastic)";
  if (field.name == "gap") return "must be finite and >= 0";
  if (field.name.starts_with("m")) return "must be in [" + value_text(kMinMass) + ", " + value_text(kMaxMass) + "] kg";
  return "must be finite and > 0";
}

std::optional<std::string> apply_physical(Case& c) {
  const Physical& p = c.physical;
  for (const PhysicalField& f : kPhysicalFields) {
    const double x = p.*f.member;
    const bool needed = f.name == "t0" || f.name == "gap" || f.name == "t1" || f.name == "t2";
    if (!used_by(f, c.scene)) {
      if (given(x)) return std::string(f.name) + ": not used by scene " + std::string(name(c.scene));
      continue;
    }
    if (!given(x)) {
      if (needed) return std::string(f.name) + ": required by a case in physical units";
      continue;
    }
    if (!physical_value_ok(f, x)) return std::string(f.name) + ": " + physical_rule(f);
  }
  if (auto bad = check_scale(c)) return bad;
  const double m0 = mass_unit(c);
  const double w0 = kTwoPi / p.t0;
  c.pi2 = w0 / c.w_p;
  c.pi3 = p.gap * c.w_p * c.w_p / c.a_p;
  if (uses_body1(c.scene)) {
    c.pi5 = p.t1 / p.t0;  // w0 / w1
    c.pi6 = given(p.m1) ? m0 / p.m1 : 1.0;
  }
  if (uses_body2(c.scene)) {
    c.pi7 = p.t2 / p.t0;
    c.pi8 = given(p.m2) ? m0 / p.m2 : 1.0;
  }
  // Not given: elastic (Case's own default, infinity).
  const double to_pi = c.w_p * c.w_p / c.a_p;
  for (const auto& [uy, pi_y] : {std::pair{p.uy0, &Case::pi_y0}, {p.uy1, &Case::pi_y1}, {p.uy2, &Case::pi_y2},
                                 {p.uy, &Case::pi_y}})
    if (given(uy)) c.*pi_y = uy * to_pi;
  return std::nullopt;
}

namespace {

// How a Pi term follows from the physical fields (cases/README.md, "Physical units").
std::string_view formula(std::string_view pi) {
  if (pi == "pi2") return "2 pi / (t0 w_p)";
  if (pi == "pi3") return "gap w_p^2 / a_p";
  if (pi == "pi5") return "t1 / t0";
  if (pi == "pi6") return "m0 / m1";
  if (pi == "pi7") return "t2 / t0";
  if (pi == "pi8") return "m0 / m2";
  return "u_y w_p^2 / a_p";  // the yield displacements
}

}  // namespace

std::string physical_reason(const Case& c, const std::string& field_reason) {
  const std::size_t colon = field_reason.find(':');
  if (colon == std::string::npos || !physical(c)) return field_reason;
  const std::string_view pi = std::string_view(field_reason).substr(0, colon);
  for (const PhysicalField& f : kPhysicalFields) {
    if (f.pi != pi || !used_by(f, c.scene)) continue;
    const auto term = std::find_if(kCaseFields.begin(), kCaseFields.end(),
                                   [&](const CaseField& cf) { return cf.name == pi; });
    const std::string value = term == kCaseFields.end() ? std::string("?") : value_text(term->get(c));
    return std::string(f.name) + ": gives " + std::string(pi) + " = " + std::string(formula(pi)) + " = " + value +
           " (" + field_reason + ")";
  }
  return field_reason;
}

double default_w_p(const Case& c) {
  if (c.pulse == PulseShape::record && c.samples) return c.samples->mean_frequency();
  return std::numeric_limits<double>::quiet_NaN();
}

double stiffness_pi_term(const Case& c, double k, bool hertz) {
  // make_system's m0 is 1; the user's is the unit the masses were given in.
  const System s = make_system(c);
  const double K = k / (mass_unit(c) * s.bodies[static_cast<std::size_t>(s.ref)].k);
  return hertz ? K * std::sqrt(s.contact_length_scale()) : K;
}

double step_pi_term(const System& s, double h) { return kTwoPi * h / s.t_min; }

}  // namespace pb
