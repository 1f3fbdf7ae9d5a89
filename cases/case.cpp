#include "cases/case.hpp"

#include <algorithm>
#include <numbers>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>

#include "cases/record.hpp"
#include "cases/text.hpp"

namespace pb {

std::string_view name(Scene s) {
  switch (s) {
    case Scene::wall: return "wall";
    case Scene::pair: return "pair";
    case Scene::row3: return "row3";
    case Scene::chain: return "chain";
  }
  return "?";
}

std::string_view name(PulseShape p) {
  switch (p) {
    case PulseShape::sine: return "sine";
    case PulseShape::cosine: return "cosine";
    case PulseShape::makris_a: return "makris-a";
    case PulseShape::makris_b: return "makris-b";
    case PulseShape::makris_c: return "makris-c";
    case PulseShape::mp: return "mp";
    case PulseShape::record: return "record";
  }
  return "?";
}

std::string_view name(Directivity d) { return d == Directivity::normal ? "normal" : "reverse"; }

std::optional<Scene> parse_scene(std::string_view s) {
  for (Scene v : {Scene::wall, Scene::pair, Scene::row3, Scene::chain})
    if (name(v) == s) return v;
  return std::nullopt;
}

std::optional<PulseShape> parse_pulse(std::string_view s) {
  for (PulseShape v : {PulseShape::sine, PulseShape::cosine, PulseShape::makris_a, PulseShape::makris_b,
                       PulseShape::makris_c, PulseShape::mp, PulseShape::record})
    if (name(v) == s) return v;
  return std::nullopt;
}

std::optional<Directivity> parse_directivity(std::string_view s) {
  for (Directivity v : {Directivity::normal, Directivity::reverse})
    if (name(v) == s) return v;
  return std::nullopt;
}

int body_count(const Case& c) {
  switch (c.scene) {
    case Scene::wall: return 1;
    case Scene::pair: return 2;
    case Scene::row3: return 3;
    case Scene::chain: return c.bodies;
  }
  return 0;
}
int contact_count(const Case& c) { return c.scene == Scene::wall ? 1 : body_count(c) - 1; }
bool uses_body1(Scene s) { return s != Scene::wall; }
bool uses_body2(Scene s) { return s == Scene::row3; }

namespace {

bool positive(double x) { return std::isfinite(x) && x > 0.0; }
bool within(double x, double lo, double hi) { return std::isfinite(x) && x >= lo && x <= hi; }

// A bound or a value as a message shows it: "1e4", "1.25e308", "1e-12", "1000", "0.5".
std::string text(double x) {
  const double a = std::abs(x);
  const bool scientific = a != 0.0 && (a >= 1e4 || a < 1e-4);
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, scientific ? "%.6e" : "%.6g", x);
  std::string s = buffer;
  const std::size_t e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mantissa = s.substr(0, e);
  if (mantissa.find('.') != std::string::npos) {
    mantissa.erase(mantissa.find_last_not_of('0') + 1);
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  std::string exponent = s.substr(e + 1);
  const bool negative = exponent.front() == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

// The numbers of the loads beyond the paper's: each only with its own pulse.
//   cycles in [1, 100]: Cn pulses in the literature have 1 to 3 cycles; 100 keeps a run within
//     the duration bound at any Pi2.
//   mp_gamma in (1, 100]: Mavroeidis and Papageorgiou require gamma > 1 (their fits lie in
//     1.5..3); the pulse lasts gamma T_p.
//   mp_nu within +-360 degrees: a phase.
// A record's scaling (cases/record_scale.hpp): a factor in [1e-6, 1e6] (a record's peak must stay
// within 1e6 of a_p, above), or one target, pga or sa with sa_period, each finite and > 0.
std::optional<std::string> check_scaling(const Case& c) {
  const bool rec = c.pulse == PulseShape::record;
  const auto given = [](double x) { return !std::isnan(x); };
  if (!rec) {
    if (c.record_scale != 1.0) return std::string("record_scale: only a record is scaled");
    for (const auto& [name, x] : {std::pair{"pga", c.pga}, {"sa", c.sa}, {"sa_period", c.sa_period}})
      if (given(x)) return std::string(name) + ": only a record is scaled";
    return std::nullopt;
  }
  if (!within(c.record_scale, 1e-6, 1e6)) return std::string("record_scale: must be finite and in [1e-6, 1e6]");
  if (given(c.pga) && !(std::isfinite(c.pga) && c.pga > 0.0)) return std::string("pga: must be finite and > 0 (m/s^2)");
  if (given(c.sa) && !(std::isfinite(c.sa) && c.sa > 0.0)) return std::string("sa: must be finite and > 0 (m/s^2)");
  if (given(c.sa_period) && !(std::isfinite(c.sa_period) && c.sa_period > 0.0))
    return std::string("sa_period: must be finite and > 0 (s)");
  if (given(c.sa) != given(c.sa_period)) return std::string(given(c.sa) ? "sa_period: required by sa" : "sa: sa_period is its period; give sa too");
  if (given(c.pga) && given(c.sa)) return std::string("sa: not with pga (scale the record to one target)");
  if (c.samples && c.samples->scale != c.record_scale)
    return "record_scale: " + text(c.record_scale) + " but the samples carry " + text(c.samples->scale) +
           " (scale_record was not applied)";
  return std::nullopt;
}

std::optional<std::string> check_load(const Case& c) {
  const bool mc = c.pulse == PulseShape::makris_c, mp = c.pulse == PulseShape::mp;
  const bool rec = c.pulse == PulseShape::record;
  if (mc && (c.cycles < 1 || c.cycles > kMaxCycles))
    return "cycles: the makris-c pulse needs 1 to " + std::to_string(kMaxCycles) + " cycles";
  if (!mc && c.cycles != 0) return "cycles: only the makris-c pulse has cycles";
  if (mp) {
    if (!std::isfinite(c.mp_gamma) || c.mp_gamma <= 1.0 || c.mp_gamma > kMaxMpGamma)
      return "mp_gamma: must be in (1, " + text(kMaxMpGamma) + "]";
    if (!within(c.mp_nu, -kMaxMpNu, kMaxMpNu)) return "mp_nu: must be finite and in [-360, 360] (degrees)";
  } else {
    if (c.mp_gamma != 0.0) return "mp_gamma: only the mp pulse has it";
    if (c.mp_nu != 0.0) return "mp_nu: only the mp pulse has it";
  }
  if (rec && c.record.empty()) return "record: required by pulse record (the file of the accelerogram)";
  if (rec && c.samples == nullptr) return "record: the file " + clip(c.record) + " was not read";
  if (rec && !(c.samples->peak >= kMinRecordPeak * c.a_p && c.samples->peak <= kMaxRecordPeak * c.a_p))
    return "a_p: the record's peak (" + text(c.samples->peak) + ") must be within a factor 1e6 of a_p (a record "
           "1e-320 of a_p hung the reference: its response is below any tolerance)";
  if (!rec && !c.record.empty()) return "record: only the record pulse reads a record";
  if (auto bad = check_scaling(c)) return bad;
  return std::nullopt;
}

// The yield displacements and alpha (cases/README.md, "Yielding"):
//   pi_y in [1e-6, inf]: the reference locates a yield like a contact, with gaps below
//     1e-10 a_p / w_p^2 counted as closed; a yield displacement 1e4 times that is still
//     resolved to 1e-6 of itself. Infinity is an elastic body.
//   alpha in [0, 1): the spec's; 1 would be elastic, and above it the branch would soften
//     the body on unloading.
std::optional<std::string> check_yielding(const Case& c) {
  for (const auto& [value, field, used] :
       {std::tuple{c.pi_y0, "pi_y0", c.scene != Scene::chain},
        {c.pi_y1, "pi_y1", c.scene == Scene::pair || c.scene == Scene::row3}, {c.pi_y2, "pi_y2", c.scene == Scene::row3},
        {c.pi_y, "pi_y", c.scene == Scene::chain}}) {
    if (std::isinf(value) && value > 0.0) continue;
    if (!used) return std::string(field) + ": not used by scene " + std::string(name(c.scene));
    if (!(value >= kMinPiY))
      return std::string(field) + ": a yield displacement must be >= " + text(kMinPiY) + " (inf: elastic)";
  }
  if (!(c.alpha >= 0.0 && c.alpha < 1.0)) return "alpha: post-yield stiffness ratio must be in [0, 1)";
  return std::nullopt;
}

}  // namespace

std::optional<std::string> check_scale(const Case& c) {
  if (!positive(c.a_p)) return "a_p: must be finite and > 0";
  if (!within(c.a_p, kMinAp, kMaxAp)) return "a_p: must be in [" + text(kMinAp) + ", " + text(kMaxAp) + "]";
  if (!positive(c.w_p)) return "w_p: must be finite and > 0";
  if (!within(c.w_p, kMinWp, kMaxWp)) return "w_p: must be in [" + text(kMinWp) + ", " + text(kMaxWp) + "]";
  return std::nullopt;
}

namespace {

// Each value alone: the spec's rules (cases/README.md), then the bounds of the domain.
//   pi3 <= 1e6: a gap is delta + u_R - u_L, rounded to about 1e-16 delta; the reference
//     counts a gap below 1e-10 a_p / w_p^2 as closed, and at pi3 = 1e6 the rounding
//     reaches that tolerance, so a wider gap could never be seen to close.
//   n_free <= 1000: three orders beyond the shipped 100; with the contrast it bounds the
//     length of a run (check_duration).
//   |kick| <= 1e6: velocities stay within 1e6 of the pulse's velocity scale a_p / w_p.
//   a_p in [1e-12, 1e12], w_p in [1e-6, 1e6]: with the contrasts below, lengths
//     a_p / w_p^2 lie in [1e-24, 1e24], velocities in [1e-18, 1e18], frequencies in
//     [1e-10, 1e10], stiffnesses m w^2 in [1e-26, 1e26] and energies m (a_p / w_p)^2 in
//     [1e-42, 1e42]: squares and products of any two of them stay more than 100 orders
//     of magnitude away from overflow (1e308) and underflow (1e-308), so every absolute
//     quantity of a run is as exact as at a_p = w_p = 1 and Pi1 is self-similar (tested
//     to 1e-9 at the corners). Far outside, a_p = 1e200 lost 3 % of the no-contact Pi1
//     and w_p = 1e100 gave Pi1 = 0.
std::optional<std::string> check_values(const Case& c) {
  if (!positive(c.pi2)) return "pi2: must be finite and > 0";
  if (!std::isfinite(c.pi3) || c.pi3 < 0.0) return "pi3: gap must be finite and >= 0";
  if (c.pi3 > kMaxPi3) return "pi3: gap must be <= " + text(kMaxPi3) + " (no pulse closes a wider one)";
  if (!std::isfinite(c.eps) || c.eps < 0.0 || c.eps > 1.0) return "eps: must be in [0, 1]";
  if (uses_body1(c.scene)) {
    if (!positive(c.pi5)) return "pi5: frequency ratio must be finite and > 0";
    if (!positive(c.pi6)) return "pi6: mass ratio must be finite and > 0";
  }
  if (uses_body2(c.scene)) {
    if (!positive(c.pi7)) return "pi7: frequency ratio must be finite and > 0";
    if (!positive(c.pi8)) return "pi8: mass ratio must be finite and > 0";
  }
  if (c.scene == Scene::chain) {
    if (c.bodies < 2 || c.bodies > kMaxChainBodies)
      return "bodies: a chain needs 2 to " + std::to_string(kMaxChainBodies) + " bodies";
    if (!within(c.kick, -kMaxKick, kMaxKick))
      return "kick: must be finite and in [-" + text(kMaxKick) + ", " + text(kMaxKick) + "]";
  } else {
    if (c.bodies != 0) return "bodies: only the chain scene has a body count";
    if (c.kick != 0.0) return "kick: only the chain scene starts moving";
  }
  // The closed forms of the reference are those of an underdamped oscillator.
  if (!std::isfinite(c.xi) || c.xi < 0.0 || c.xi >= 1.0) return "xi: damping ratio must be in [0, 1)";
  if (!positive(c.n_free)) return "n_free: must be finite and > 0";
  if (c.n_free > kMaxNFree) return "n_free: must be <= " + text(kMaxNFree);
  if (auto bad = check_scale(c)) return bad;
  if (auto bad = check_yielding(c)) return bad;
  return check_load(c);
}

// The smallest and largest of some positive numbers.
struct Span {
  double lo, hi;
  void add(double x) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  double contrast() const { return hi / lo; }  // inf when a ratio under- or overflowed
};

// The natural frequencies over w_p, body 0 first, then those of the other bodies in the
// order their ratios are checked, so that a contrast names the term that widened it.
//   frequencies (and w_p) within 1e4: the run lasts t_end / t_min <= (1 + n_free) 1e4
//     shortest periods, and an exact solution is resolved over that span of time scales
//     (the shipped sets reach 1e3: Pi2 0.1..10 with Pi5 0.01..100).
//   masses within 1e6: an impact between masses that far apart changes the heavy body's
//     velocity by 1e-6 of the light one's, still 5e9 ulps; the shipped sets reach 1e2.
std::optional<std::string> check_contrasts(const Case& c) {
  const auto too_wide = [](std::string_view field, std::string_view what, const Span& s, double bound) {
    return std::string(field) + ": the " + std::string(what) + " span a contrast (max/min) of " + text(s.contrast()) +
           ", more than " + text(bound);
  };
  constexpr std::string_view kFrequencies = "natural frequencies and w_p";
  Span w{1.0, 1.0};
  w.add(c.pi2);
  if (w.contrast() > kMaxFrequencyContrast) return too_wide("pi2", kFrequencies, w, kMaxFrequencyContrast);
  Span m{1.0, 1.0};
  if (uses_body1(c.scene)) {
    w.add(c.pi2 / c.pi5);
    if (w.contrast() > kMaxFrequencyContrast) return too_wide("pi5", kFrequencies, w, kMaxFrequencyContrast);
    m.add(1.0 / c.pi6);
    if (m.contrast() > kMaxMassContrast) return too_wide("pi6", "masses", m, kMaxMassContrast);
  }
  if (uses_body2(c.scene)) {
    w.add(c.pi2 / c.pi7);
    if (w.contrast() > kMaxFrequencyContrast) return too_wide("pi7", kFrequencies, w, kMaxFrequencyContrast);
    m.add(1.0 / c.pi8);
    if (m.contrast() > kMaxMassContrast) return too_wide("pi8", "masses", m, kMaxMassContrast);
  }
  return std::nullopt;
}

// t_end / t_min = (T_p + n_free T_max) / min(T_p, T_min of the bodies) <= 1e6: a
// time-stepper at its default 64 steps per shortest period then takes at most 6.4e7
// steps, within the 1e8 its solvers allow by default, and the times of a run are still
// resolved to 2e-9 of its shortest period (8 ulps of t_end, the reference's finest
// search window). Within the contrast bound only n_free can exceed it (n_free <= 99
// never does).
//
// The loads beyond the paper's last longer than T_p (load_periods): a record's length
// counts, in periods T_p, as the pulse's one period does.
std::optional<std::string> check_duration(const Case& c) {
  Span body{c.pi2, c.pi2};  // body frequencies over w_p
  if (uses_body1(c.scene)) body.add(c.pi2 / c.pi5);
  if (uses_body2(c.scene)) body.add(c.pi2 / c.pi7);
  const double periods = (load_periods(c) + c.n_free / body.lo) * std::max(1.0, body.hi);
  if (periods > kMaxPeriodsPerRun)
    return "n_free: the run would last " + text(periods) + " shortest periods (t_end / t_min), more than " +
           text(kMaxPeriodsPerRun);
  return std::nullopt;
}

}  // namespace

bool yields(const Case& c) {
  return std::isfinite(pi_y_ref(c)) ||
         (uses_body1(c.scene) && c.scene != Scene::chain && std::isfinite(c.pi_y1)) ||
         (uses_body2(c.scene) && std::isfinite(c.pi_y2));
}

double pi_y_ref(const Case& c) { return c.scene == Scene::chain ? c.pi_y : c.pi_y0; }

double load_periods(const Case& c) {
  switch (c.pulse) {
    case PulseShape::makris_c: return c.cycles + 0.5;  // (n + 1/2 - phi_n / pi), phi_n > 0
    case PulseShape::mp: return c.mp_gamma;
    case PulseShape::record:
      return c.samples ? c.samples->length() * c.w_p / (2.0 * std::numbers::pi) : 1.0;
    default: return 1.0;
  }
}

std::optional<std::string> validate(const Case& c) {
  if (auto bad = check_values(c)) return bad;
  if (auto bad = check_contrasts(c)) return bad;
  return check_duration(c);
}

}  // namespace pb
