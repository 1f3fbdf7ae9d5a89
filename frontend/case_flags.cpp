#include "frontend/case_flags.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string_view>

#include "cases/buildings_set.hpp"
#include "cases/case_set.hpp"
#include "cases/fields.hpp"
#include "cases/physical.hpp"
#include "cases/record.hpp"
#include "cases/record_scale.hpp"
#include "cases/text.hpp"
#include "frontend/errors.hpp"

namespace pb::app {

namespace {

template <class T>
T parsed(std::string_view flag, const std::string& text, std::optional<T> value, std::string_view choices) {
  if (!value)
    throw BadInput(std::string(flag) + ": unknown value '" + clip(text) + "' (one of " + std::string(choices) + ")");
  return *value;
}

// The point --point names among n (0 when there is one and --point is not given).
std::size_t chosen_point(const GivenFlag& given, const CaseFlags& flags, std::size_t n) {
  const std::string& file = flags.case_file;
  if (n == 0) throw BadInput(file + ": no cases");
  if (given("--point")) {
    if (flags.point < 0 || static_cast<std::size_t>(flags.point) >= n)
      throw BadInput("--point: " + std::to_string(flags.point) + " is out of range (" + file + " has points 0.." +
                     std::to_string(n - 1) + ")");
    return static_cast<std::size_t>(flags.point);
  }
  if (n > 1)
    throw BadInput("--point: " + file + " has " + std::to_string(n) + " cases; choose one with --point 0.." +
                   std::to_string(n - 1));
  return 0;
}

ChosenCase case_from_file(const GivenFlag& given, const CaseFlags& flags, bool buildings) {
  for (std::string_view flag : {"--scene", "--pulse", "--directivity"})
    if (given(flag)) throw BadInput(std::string(flag) + ": cannot be combined with --case-file");
  for (const CaseField& field : kCaseFields)
    if (given(flag_of(field))) throw BadInput(flag_of(field) + ": cannot be combined with --case-file");
  for (const CaseAlias& alias : kCaseAliases)
    if (given(flag_of(alias.name))) throw BadInput(flag_of(alias.name) + ": cannot be combined with --case-file");
  for (const PhysicalField& field : kPhysicalFields)
    if (given(flag_of(field.name))) throw BadInput(flag_of(field.name) + ": cannot be combined with --case-file");
  const std::string file = flags.case_file;
  // A buildings case set: its point, where the caller solves the scene.
  if (std::optional<BuildingsSet> b = load_buildings_set(file)) {
    if (!buildings) throw BadInput(file + ": " + buildings_not_here_reason());
    const std::size_t point = chosen_point(given, flags, b->points.size());
    ChosenCase out{{}, point, file};
    out.building = std::make_shared<const BuildingCase>(std::move(b->points[point]));
    return out;
  }
  const CaseSet set = load_case_set(file);
  const std::size_t point = chosen_point(given, flags, set.cases.size());
  const Case& c = set.cases[point];
  if (auto bad = validate(c)) throw BadInput(file + ": point " + std::to_string(point) + ": " + *bad);
  return {c, point, file};
}

// A message about a field the user gave through its alias (--tp 1e-300 gives w_p = 6.3e300,
// out of the domain) names the alias, with the value it gave; any other message as it is.
std::string as_given(const std::string& message, const Case& c, const GivenFlag& given) {
  for (const CaseAlias& alias : kCaseAliases) {
    const std::string field = flag_of(alias.field), flag = flag_of(alias.name);
    if (!message.starts_with(field + ":") || !given(flag) || given(field)) continue;
    const auto f = std::find_if(kCaseFields.begin(), kCaseFields.end(),
                                [&](const CaseField& cf) { return cf.name == alias.field; });
    char value[32];
    std::snprintf(value, sizeof value, "%.6g", f == kCaseFields.end() ? std::nan("") : f->get(c));
    return flag + ": gives " + std::string(alias.field) + " = " + value + " (" + std::string(alias.field) +
           message.substr(field.size()) + ")";
  }
  return message;
}

ChosenCase case_from_flags(const GivenFlag& given, const CaseFlags& flags) {
  if (given("--point")) throw BadInput("--point: only used with --case-file");
  // A case in physical units (cases/physical.hpp) gives the Pi terms its fields replace,
  // never beside them: the first physical flag given names the way the case was given.
  std::string physical_flag;
  for (const PhysicalField& field : kPhysicalFields)
    if (physical_flag.empty() && given(flag_of(field.name))) physical_flag = flag_of(field.name);
  // In physical units the load is as recorded or described: --directivity defaults to normal.
  for (std::string_view flag : {"--scene", "--pulse", "--directivity"})
    if (!given(flag) && !(flag == "--directivity" && !physical_flag.empty()))
      throw BadInput(std::string(flag) + ": required (or give --case-file)");

  Case c;
  c.scene = parsed("--scene", flags.scene, parse_scene(flags.scene), "wall, pair, row3, chain");
  c.pulse = parsed("--pulse", flags.pulse, parse_pulse(flags.pulse),
                   "sine, cosine, makris-a, makris-b, makris-c, mp, record");
  if (given("--directivity"))
    c.directivity =
        parsed("--directivity", flags.directivity, parse_directivity(flags.directivity), "normal, reverse");
  const std::string scene(name(c.scene));
  const auto replaced = [&](const CaseField& field) {
    for (const PhysicalField& p : kPhysicalFields)
      if (!physical_flag.empty() && p.pi == field.name) return true;
    return false;
  };
  // A field the scene and pulse use is taken from its flag (a required one must be given);
  // one they do not use must not be given, and keeps Case's default.
  for (const CaseField& field : kCaseFields) {
    const std::string flag = flag_of(field);
    const bool used = used_by(field, c);
    const auto user = [&] { return pulse_use(field.use) ? "pulse " + std::string(name(c.pulse)) : "scene " + scene; };
    if (replaced(field)) {
      if (given(flag)) throw BadInput(flag + ": not with " + physical_flag + " (a case is given in Pi terms or in physical units, not both)");
      continue;
    }
    if (used && field.required && !given(flag))
      throw BadInput(flag + (field.use == FieldUse::every ? ": required (or give --case-file)" : ": required by " + user()));
    if (!used && given(flag)) throw BadInput(flag + ": not used by " + user());
    // NaN is a scaling target's "not given": --pga nan would scale nothing without a word.
    if (used && given(flag) && field.number && std::isnan(flags.numbers.*field.number))
      throw BadInput(flag + ": must be finite and > 0 (got nan)");
    if (used) copy_field(field, flags.numbers, c);
  }
  // An alias gives its field (--tp gives --w-p), never beside it.
  for (std::size_t a = 0; a < kCaseAliases.size(); ++a) {
    const CaseAlias& alias = kCaseAliases[a];
    const std::string flag = flag_of(alias.name), target = flag_of(alias.field);
    if (!given(flag)) continue;
    if (given(target)) throw BadInput(flag + ": not with " + target + " (give one of them)");
    const double x = flags.aliases[a];
    if (!(std::isfinite(x) && x > 0.0)) throw BadInput(flag + ": must be finite and > 0");
    for (const CaseField& field : kCaseFields)
      if (field.name == alias.field) c.*field.number = alias.convert(x);
  }
  if (c.pulse == PulseShape::record) {
    // A record's Pi terms: w_p the user's (a pulse period read from the record) or else the
    // record's mean frequency 2 pi / T_m, a_p its peak unless given. The record is read here, once.
    try {
      c.samples = read_record(c.record);
    } catch (const RecordError& e) {
      throw BadInput("--record: " + std::string(e.what()));
    }
    if (!physical_flag.empty() && given("--a-p")) throw BadInput("--a-p: " + record_a_p_reason(true));
    if (auto bad = scale_record(c)) throw BadInput(case_flag_message(*bad));
    if (!given("--a-p")) c.a_p = c.samples->peak;
    if (!given("--w-p") && !given("--tp")) {
      if (!std::isfinite(c.samples->t_m))
        throw BadInput("--tp: required by --record " + clip(c.record) + ": " + no_mean_period_reason());
      c.w_p = c.samples->mean_frequency();
    }
  }
  if (!physical_flag.empty()) {
    for (const PhysicalField& field : kPhysicalFields) {
      if (!given(flag_of(field.name))) continue;
      if (!used_by(field, c.scene)) throw BadInput(flag_of(field.name) + ": not used by scene " + scene);
      // NaN is Physical's "not given": --uy0 nan ran elastic, as if the flag were not there.
      const double x = flags.numbers.physical.*field.member;
      if (std::isnan(x)) throw BadInput(flag_of(field.name) + ": " + physical_rule(field) + " (got nan)");
      c.physical.*field.member = x;
    }
    // The unit of the Pi terms: a pulse's own a_p and period; a record's peak and mean period
    // unless given (any unit gives the same physical case).
    if (c.pulse != PulseShape::record && !given("--a-p"))
      throw BadInput("--a-p: required by a case in physical units (the pulse's peak acceleration, m/s^2)");
    if (!given("--w-p") && !given("--tp")) {
      if (c.pulse != PulseShape::record)
        throw BadInput("--tp: required by a case in physical units (the pulse's period, s; or --w-p)");
      c.w_p = default_w_p(c);
      if (!std::isfinite(c.w_p))
        throw BadInput("--tp: required: " + c.record + " has no mean period (no Fourier amplitude in 0.25-20 Hz)");
    }
    if (auto bad = apply_physical(c)) throw BadInput(as_given(case_flag_message(*bad), c, given));
  }
  // A Pi term out of the domain is named by the physical flag that gave it (--t0, not --pi2).
  if (auto bad = validate(c)) throw BadInput(as_given(case_flag_message(physical_reason(c, *bad)), c, given));
  return {c, 0, {}};
}

}  // namespace

void add_case_flags(CLI::App& command, CaseFlags& f) {
  command.add_option("--scene", f.scene, "Scene: wall, pair, row3 or chain");
  command.add_option("--pulse", f.pulse, "Pulse: sine, cosine, makris-a, makris-b, makris-c, mp or record");
  command.add_option("--directivity", f.directivity, "Directivity: normal or reverse");
  for (const CaseField& field : kCaseFields) {
    const std::string flag = flag_of(field), help(field.help);
    CLI::Option* option = field.number    ? command.add_option(flag, f.numbers.*field.number, help)
                          : field.integer ? command.add_option(flag, f.numbers.*field.integer, help)
                                          : command.add_option(flag, f.numbers.*field.text, help);
    if (!field.required) option->capture_default_str();
  }
  for (std::size_t a = 0; a < kCaseAliases.size(); ++a)
    command.add_option(flag_of(kCaseAliases[a].name), f.aliases[a], std::string(kCaseAliases[a].help));
  for (const PhysicalField& field : kPhysicalFields)
    command.add_option(flag_of(field.name), f.numbers.physical.*field.member, std::string(field.help));
  command.add_option("--case-file", f.case_file, "Take the case from a case-set file instead of the flags above");
  command.add_option("--point", f.point, "Which case of --case-file (0-based; needed when it has several)");
}

ChosenCase chosen_case(const GivenFlag& given, const CaseFlags& flags) {
  return given("--case-file") ? case_from_file(given, flags, false) : case_from_flags(given, flags);
}

ChosenCase chosen_case_or_buildings(const GivenFlag& given, const CaseFlags& flags) {
  return given("--case-file") ? case_from_file(given, flags, true) : case_from_flags(given, flags);
}

ChosenCase chosen_case(const CLI::App& command, const CaseFlags& flags) {
  return chosen_case([&](std::string_view flag) { return command.count(std::string(flag)) > 0; }, flags);
}

void validate_case_set(const CaseList& cases, const std::string& file) {
  if (cases.empty()) throw BadInput(file + ": no cases");
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (auto bad = validate(cases[i])) throw BadInput(file + ": point " + std::to_string(i) + ": " + *bad);
}

std::string case_flag_message(const std::string& field_reason) {
  const std::size_t colon = field_reason.find(':');
  if (colon == std::string::npos) return field_reason;
  std::string flag = "--" + field_reason.substr(0, colon);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag + field_reason.substr(colon);
}

}  // namespace pb::app
