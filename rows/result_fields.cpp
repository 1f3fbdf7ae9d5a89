#include "rows/result_fields.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "cases/physical.hpp"

namespace pb {

namespace {

// A number written as an empty field where it is infinite (a gap that never closed).
double finite_or_missing(double x) { return std::isinf(x) ? std::numeric_limits<double>::quiet_NaN() : x; }

using T = ResultType;
using P = Place;

std::vector<double> scaled(std::vector<double> x, double unit) {
  for (double& v : x) v *= unit;
  return x;
}

// A length of the no-contact motion, Row::NAME: its Pi term as NAME_pi, and NAME_m in metres
// (made from it, as peak_m from pi1).
#define SEPARATION(NAME)                                                                               \
  ResultField{.name = #NAME "_pi", .type = T::number, .place = P::separation,                          \
              .made = [](const Row& r) { return r.NAME; }, .store = [](Row& r, double x) { r.NAME = x; }}, \
      ResultField {                                                                                    \
    .name = #NAME "_m", .type = T::number, .place = P::separation,                                     \
    .made = [](const Row& r) { return r.NAME * length_unit(r.input); }                                 \
  }

constexpr auto kTable = std::to_array<ResultField>({
    {.name = "solver", .type = T::text, .place = P::middle,
     .text = [](const Row& r) { return std::string_view(r.solver); },
     .store_text = [](Row& r, std::string_view x) { r.solver = x; }},
    {.name = "variant", .type = T::text, .place = P::middle,
     .text = [](const Row& r) { return std::string_view(r.variant); },
     .store_text = [](Row& r, std::string_view x) { r.variant = x; }},
    // A JSON object of named values (SolverInfo::describe): --json and Python carry it as one.
    {.name = "settings", .type = T::object, .place = P::middle,
     .text = [](const Row& r) { return std::string_view(r.settings); },
     .store_text = [](Row& r, std::string_view x) { r.settings = x; }},
    {.name = "status", .type = T::status, .place = P::middle, .answer = "status"},
    {.name = "pi1", .type = T::number, .place = P::middle, .answer = "pi1", .real = &Result::pi1},
    {.name = "pi1_no_contact", .type = T::number, .place = P::middle,
     .made = [](const Row& r) { return r.pi1_no_contact; }, .store = [](Row& r, double x) { r.pi1_no_contact = x; }},
    // The time of the maximum, in the case's time unit (w_p t_max is dimensionless): no column.
    {.name = "t_max", .type = T::number, .place = P::none, .answer = "t_max", .real = &Result::t_max},
    {.name = "impacts", .type = T::count, .place = P::middle, .answer = "impacts", .whole = &Result::impacts, .missing = 0},
    {.name = "contact_phases", .type = T::count, .place = P::middle, .answer = "contact_phases",
     .whole = &Result::contact_phases, .missing = 0},
    {.name = "steps", .type = T::count, .place = P::middle, .answer = "steps", .whole = &Result::steps, .missing = 0},
    // Over a_p / w_p^2 in a row; an answer's is the system's own (infinite, or absent: none closed).
    {.name = "min_gap", .type = T::number, .place = P::middle, .answer = "min_gap", .real = &Result::min_gap,
     .made = [](const Row& r) { return finite_or_missing(min_gap_ratio(r)); },
     .store = [](Row& r, double x) {
       r.result.min_gap = x;
       r.length_scale = 1.0;
     },
     .missing = std::numeric_limits<double>::infinity()},
    {.name = "seconds", .type = T::number, .place = P::middle,
     .made = [](const Row& r) { return r.seconds; }, .store = [](Row& r, double x) { r.seconds = x; }},
    {.name = "cpu_seconds", .type = T::number, .place = P::middle,
     .made = [](const Row& r) { return r.cpu_seconds; }, .store = [](Row& r, double x) { r.cpu_seconds = x; }},
    {.name = "message", .type = T::text, .place = P::middle, .answer = "message",
     .text = [](const Row& r) { return std::string_view(r.result.message); },
     .store_text = [](Row& r, std::string_view x) { r.result.message = x; }},
    {.name = "wh", .type = T::number, .place = P::tail,
     .made = [](const Row& r) { return r.wh; }, .store = [](Row& r, double x) { r.wh = x; }},
    // A record's step over its sampling interval DT (empty for a pulse or a solver with no fixed
    // step): the step rule `record` (Settings::steps_per_sample) makes it 1/m.
    {.name = "h_over_dt", .type = T::number, .place = P::record_step, .made = &h_over_dt},
    {.name = "energy_excess", .type = T::number, .place = P::tail, .answer = "energy_excess",
     .real = &Result::energy_excess},
    {.name = "penetration", .type = T::number, .place = P::tail, .made = &penetration},
    {.name = "isolated_impacts", .type = T::count, .place = P::tail, .answer = "isolated_impacts",
     .whole = &Result::isolated_impacts, .missing = 0},
    {.name = "restitution_low", .type = T::number, .place = P::tail, .answer = "restitution_low",
     .real = &Result::restitution_low},
    {.name = "restitution_high", .type = T::number, .place = P::tail, .answer = "restitution_high",
     .real = &Result::restitution_high},
    {.name = "penetration_steps", .type = T::number, .place = P::tail, .json = false,
     .made = [](const Row& r) { return r.penetration_steps; }, .store = [](Row& r, double x) { r.penetration_steps = x; }},
    {.name = "cpu_seconds_low", .type = T::number, .place = P::tail, .json = false,
     .made = [](const Row& r) { return r.cpu_seconds_low; }, .store = [](Row& r, double x) { r.cpu_seconds_low = x; }},
    {.name = "cpu_seconds_high", .type = T::number, .place = P::tail, .json = false,
     .made = [](const Row& r) { return r.cpu_seconds_high; }, .store = [](Row& r, double x) { r.cpu_seconds_high = x; }},
    // A file from before repetitions has one timing.
    {.name = "repetitions", .type = T::count, .place = P::tail, .json = false,
     .made = [](const Row& r) { return static_cast<double>(r.repetitions); },
     .store = [](Row& r, double x) { r.repetitions = static_cast<int>(x); }, .missing = 1},
    // A time-stepper's largest |g'| (Result::gap_rate_max): the answer's alone, penetration_steps shows it.
    {.name = "gap_rate_max", .type = T::number, .place = P::none, .json = false, .answer = "gap_rate_max",
     .real = &Result::gap_rate_max},
    // The verdict of kit/verdict.hpp: true or false for a run that ended ok, empty otherwise
    // (and in a file from before it); unresolved its reasons.
    {.name = "resolved", .type = T::verdict, .place = P::verdict},
    {.name = "unresolved", .type = T::text, .place = P::verdict,
     .text = [](const Row& r) { return std::string_view(r.result.unresolved); },
     .store_text = [](Row& r, std::string_view x) { r.result.unresolved = x; }},
    // Body 0's ductility demand, Pi1 over its Pi_y (empty for an elastic case).
    {.name = "mu", .type = T::number, .place = P::yielding, .made = &ductility},
    // An answer carries these for a yielding case alone (protocol.cpp).
    {.name = "residual", .type = T::number, .place = P::yielding, .answer = "residual", .real = &Result::residual},
    {.name = "hysteretic", .type = T::number, .place = P::yielding, .answer = "hysteretic", .real = &Result::hysteretic},
    // In the case's units (s, m, kg, N; cases/physical.hpp has the units of length and mass
    // that turn Pi terms into them), beside the Pi terms: Pi terms times a unit are made
    // again when read; the solver's own times and velocities are read.
    {.name = "peak_m", .type = T::number, .place = P::physical,
     .made = [](const Row& r) { return r.result.pi1 * length_unit(r.input); }},
    {.name = "h_s", .type = T::number, .place = P::physical, .answer = "step", .real = &Result::step},
    {.name = "first_impact_s", .type = T::number, .place = P::physical, .real = &Result::first_impact},
    {.name = "impact_velocity", .type = T::number, .place = P::physical, .real = &Result::impact_velocity_max},
    {.name = "impact_velocity_pi", .type = T::number, .place = P::physical,
     .made = [](const Row& r) { return velocity_pi_term(r.input, r.result.impact_velocity_max); }},
    // Result holds it per unit of m0 (make_system's m0 is 1).
    {.name = "contact_force_max", .type = T::number, .place = P::physical,
     .made = [](const Row& r) { return r.result.contact_force_max * mass_unit(r.input); },
     .store = [](Row& r, double x) { r.result.contact_force_max = x / mass_unit(r.input); }},
    {.name = "penetration_m", .type = T::number, .place = P::physical,
     .made = [](const Row& r) { return penetration(r) * length_unit(r.input); }},
    // The external solver's own time for its solve (the answer's, or a Python callable's call),
    // and a persistent program's start, on the one row whose point started it.
    {.name = "solve_seconds", .type = T::number, .place = P::own_time, .answer = "solve_seconds",
     .real = &Result::solve_seconds},
    {.name = "startup_seconds", .type = T::number, .place = P::own_time, .real = &Result::startup_seconds},
    // A fixed-step run's estimated relative errors of Pi1 and of the fastest impact's approach
    // velocity (Result::error_estimate); empty where none was made.
    {.name = "error_estimate", .type = T::number, .place = P::estimate, .real = &Result::error_estimate},
    {.name = "error_estimate_velocity", .type = T::number, .place = P::estimate,
     .real = &Result::error_estimate_velocity},
    // The gap that avoids pounding (kit/separation.hpp), with the load as given and reversed,
    // and each rule's: Pi terms (over a_p / w_p^2) and metres; then every body's no-contact peak.
    // Body 0's residual displacement in metres (residual is its Pi term).
    {.name = "residual_m", .type = T::number, .place = P::separation,
     .made = [](const Row& r) { return r.result.residual * length_unit(r.input); }},
    SEPARATION(separation),
    SEPARATION(separation_reversed),
    SEPARATION(separation_abs),
    SEPARATION(separation_srss),
    SEPARATION(separation_ddc),
    {.name = "peaks_m", .type = T::list, .place = P::separation,
     .list = [](const Row& r) { return scaled(r.peaks, length_unit(r.input)); },
     .store_list = [](Row& r, std::vector<double> x) { r.peaks = scaled(std::move(x), 1.0 / length_unit(r.input)); }},
    {.name = "peaks_no_contact_m", .type = T::list, .place = P::separation,
     .list = [](const Row& r) { return scaled(r.peaks_no_contact, length_unit(r.input)); },
     .store_list = [](Row& r, std::vector<double> x) { r.peaks_no_contact = scaled(std::move(x), 1.0 / length_unit(r.input)); }},
});

#undef SEPARATION

}  // namespace

const std::span<const ResultField> kResultFields{kTable};

const ResultField* find_result_field(std::string_view name) {
  const auto it = std::find_if(kTable.begin(), kTable.end(), [&](const ResultField& f) { return f.name == name; });
  return it == kTable.end() ? nullptr : &*it;
}

}  // namespace pb
