// The case document (programs/protocol.hpp), written straight out as text.
//
// It was an nlohmann::ordered_json built up and dumped: 120,000 instructions a point, more than
// a third of a persistent sweep's whole work through a program that answers at once (issue 46:
// the paper-report set through bench/instant_answer.cpp, callgrind). Written field by field it
// is a tenth of that. The bytes are still the library's dump(-1) of the same object, so that no
// program sees a change: every double through the dump's own writer (nlohmann's
// detail::to_chars, its shortest round-trip form: "1.0", "0.05", "1e-07"), an integer as the
// dump writes one, and a string by the library itself unless it is plain printable ASCII
// (a record's file name may hold anything). tests/case_document_test.cpp holds the text equal
// to the ordered_json's dump on every shipped case set.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/load.hpp"
#include "cases/record.hpp"
#include "programs/compact_json.hpp"
#include "programs/protocol.hpp"

namespace pb::programs {

namespace {

// The first number of the system that is not finite, by its field name; "" when none is.
std::string non_finite_field(const System& s) {
  const std::array<std::pair<double, const char*>, 8> numbers = {{{s.delta, "contacts.gap"},
                                                                  {s.eps, "eps"},
                                                                  {s.xi, "xi"},
                                                                  {s.a_p, "a_p"},
                                                                  {s.pulse.amplitude, "load.amplitude"},
                                                                  {s.pulse.w, "load.w"},
                                                                  {s.t_end, "t_end"},
                                                                  {s.t_min, "t_min"}}};
  for (const auto& [x, field] : numbers)
    if (!std::isfinite(x)) return field;
  for (const std::vector<double>* start : {&s.u_start, &s.v_start})
    for (double x : *start)
      if (!std::isfinite(x)) return start == &s.u_start ? "bodies.u" : "bodies.v";
  return {};
}

}  // namespace

// The load by its kind (docs/external.md): the paper's pulses as they always were, a pulse
// model as its sinusoids, a record as its samples.
void write_load(CompactJson& j, const Pulse& p) {
  j.open('{');
  if (p.paper()) {
    j.key("kind").string("pulse").key("shape").string(name(p.shape)).key("amplitude").number(p.amplitude);
    j.key("w").number(p.w).key("duration").number(p.duration());
  } else if (p.record) {
    std::vector<double> a(p.record->a.size());
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = p.amplitude * p.record->a[i];
    j.key("kind").string("record").key("source").string(p.record->source).key("w").number(p.w);
    j.key("t").numbers(p.record->t).key("a").numbers(a);
  } else {
    j.key("kind").string("sinusoids").key("shape").string(name(p.shape)).key("amplitude").number(p.amplitude);
    j.key("w").number(p.w).key("duration").number(p.duration()).key("terms").open('[');
    for (std::size_t i = 0; i < static_cast<std::size_t>(p.n_waves); ++i) {
      const Sinusoid& wave = p.waves[i];
      j.open('{').key("w").number(wave.w).key("sin").number(wave.s).key("cos").number(wave.c).close('}');
    }
    j.close(']');
    if (p.shape == PulseShape::makris_c) j.key("cycles").integer(p.cycles);
    if (p.shape == PulseShape::mp) j.key("mp_gamma").number(p.mp_gamma).key("mp_nu").number(p.mp_nu);
  }
  j.close('}');
}


CaseDocument case_document(const System& s, const Settings& settings) {
  CaseDocument doc;
  for (const Body& b : s.bodies)
    if (!(b.m > 0.0 && std::isfinite(b.m)) || !std::isfinite(b.k) || !std::isfinite(b.c) || !std::isfinite(b.w)) {
      doc.error = "every body needs a finite positive mass and a finite stiffness and damping (JSON has no NaN or "
                  "infinity)";
      return doc;
    }
  if (const std::string field = non_finite_field(s); !field.empty()) {
    doc.error = field + ": must be finite (JSON has no NaN or infinity)";
    return doc;
  }
  const auto nb = static_cast<std::size_t>(s.n_bodies());
  if ((!s.u_start.empty() && s.u_start.size() != nb) || (!s.v_start.empty() && s.v_start.size() != nb)) {
    doc.error = "start state: needs one u and one v per body (or none: rest)";
    return doc;
  }
  std::string& text = doc.text;
  text.reserve(512 + 160 * nb + (s.pulse.record ? 48 * s.pulse.record->t.size() : 0));
  CompactJson j(text);
  j.open('{').key("protocol").string(kProtocol).key("version").integer(kVersion);
  j.key("bodies").open('[');
  for (std::size_t i = 0; i < nb; ++i) {
    const Body& b = s.bodies[i];
    j.open('{').key("m").number(b.m).key("k").number(b.k).key("c").number(b.c).key("w").number(b.w);
    j.key("u").number(s.u_start.empty() ? 0.0 : s.u_start[i]).key("v").number(s.v_start.empty() ? 0.0 : s.v_start[i]);
    if (b.yields()) j.key("u_y").number(b.u_y);
    j.close('}');
  }
  j.close(']').key("reference").integer(s.ref);
  j.key("contacts").open('[');
  for (int c = 0; c < s.n_contacts(); ++c) {
    j.open('{').key("left");
    if (s.left(c) == kWall) j.null();
    else j.integer(s.left(c));
    j.key("right").integer(s.right(c)).key("gap").number(s.delta).close('}');
  }
  j.close(']').key("eps").number(s.eps).key("xi").number(s.xi);
  if (s.yields()) j.key("alpha").number(s.alpha);
  j.key("load");
  write_load(j, s.pulse);
  j.key("a_p").number(s.a_p).key("length_scale").number(s.length_scale());
  j.key("t_end").number(s.t_end).key("t_min").number(s.t_min);
  j.key("step");
  if (settings.steps > 0 || settings.wh > 0.0 || settings.h_s > 0.0) j.number(time_step(s, settings, 1));
  else j.null();
  j.key("steps_per_period");
  if (settings.steps > 0) j.integer(settings.steps);
  else j.null();
  j.key("step_cap").integer(settings.step_cap).key("time_limit").number(settings.time_limit);
  j.key("history_samples").integer(settings.history_samples).key("monitor").boolean(settings.monitor);
  j.close('}');
  text += '\n';
  return doc;
}

}  // namespace pb::programs
