#include "app/run_command.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "output/output_files.hpp"
#include "cases/fields.hpp"
#include "cases/physical.hpp"
#include "cases/record.hpp"
#include "cases/text.hpp"
#include "frontend/buildings_run.hpp"
#include "frontend/contact_stiffness.hpp"
#include "frontend/errors.hpp"
#include "frontend/run_output.hpp"
#include "rows/result_fields.hpp"
#include "kit/verdict.hpp"
#include "sweep/sweep.hpp"
#include "solvers/registry.hpp"

namespace pb::app {

namespace {

void write_history(std::ostream& out, const History& h, const Case& c) {
  const std::vector<std::string> columns = history_columns(c);
  // A run that failed before its first sample leaves an empty history: header only.
  const bool empty = h.n_bodies == 0 && h.data.empty();
  if (!empty && (h.n_bodies != body_count(c) || h.n_contacts != contact_count(c)))
    throw std::runtime_error("history: the solver returned " + std::to_string(h.n_bodies) + " bodies and " +
                             std::to_string(h.n_contacts) + " contacts for scene " + std::string(name(c.scene)));
  for (std::size_t k = 0; k < columns.size(); ++k) out << (k ? "," : "") << columns[k];
  out << '\n';
  const auto width = static_cast<std::size_t>(h.row_size());
  for (std::size_t r = 0; r < h.rows(); ++r) {
    for (std::size_t k = 0; k < width; ++k) out << (k ? "," : "") << format_number(h.data[r * width + k]);
    out << '\n';
  }
}

// Six significant digits: enough to read; --json has every digit.
std::string brief(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

// The case's gap delta in metres: Pi3 times the unit of length.
double gap_m(const Row& row) { return row.input.pi3 * length_unit(row.input); }

// The results in the case's units (rows/result_fields.hpp, Place::physical): metres and
// seconds when the case was given in them, the pulse's a_p and w_p in SI otherwise.
void print_physical(std::ostream& out, const Row& row) {
  const auto number = [&](std::string_view field) { return find_result_field(field)->number(row); };
  const auto value = [&](std::string_view field) { return brief(number(field)); };
  out << "peak     " << value("peak_m") << " m (body 0)";
  // The other bodies' (Row::peaks: body 1, then body 2 of row3).
  for (std::size_t i = 1; i < row.peaks.size(); ++i)
    out << ", " << brief(row.peaks[i] * length_unit(row.input)) << " m (body " << i << ")";
  if (std::isfinite(number("h_s"))) out << ", step h = " << value("h_s") << " s";
  out << '\n';
  if (std::isfinite(number("first_impact_s")))
    out << "pounding first impact at t = " << value("first_impact_s") << " s, fastest approach "
        << value("impact_velocity") << " m/s (Pi " << value("impact_velocity_pi") << ")\n";
  else if (row.result.impacts == 0)
    out << "pounding none\n";
  if (std::isfinite(number("contact_force_max")))
    out << "contact  largest force " << value("contact_force_max") << " N, deepest penetration "
        << value("penetration_m") << " m\n";
  // The gap that avoids pounding, from the no-contact motion (kit/separation.hpp).
  if (std::isfinite(row.separation)) {
    out << "separat. " << value("separation_m") << " m avoids pounding (" << value("separation_reversed_m")
        << " m with the load reversed; the gap given: " << brief(gap_m(row)) << " m)\n";
    out << "rules    ABS " << value("separation_abs_m") << " m, SRSS " << value("separation_srss_m") << " m (EC8 0.7 SRSS "
        << brief(0.7 * number("separation_srss_m")) << " m where floors coincide), DDC " << value("separation_ddc_m")
        << " m\n";
  }
}

// The error estimate's line (Result::error_estimate), where the run has one.
void print_estimate(std::ostream& out, const Row& row) {
  const Result& r = row.result;
  if (std::isnan(r.error_estimate)) return;
  const SolverInfo* solver = find_solver(row.solver);
  out << "error    estimate " << percent(r.error_estimate) << " of Pi1";
  if (std::isfinite(r.error_estimate_velocity))
    out << ", " << percent(r.error_estimate_velocity) << " of the fastest approach";
  out << " (companion solve at 2h, order " << brief(solver ? solver->step_order : std::nan("")) << ")\n";
}

void print_summary(std::ostream& out, const Row& row) {
  const Case& c = row.input;
  const Result& r = row.result;
  out << name(c.scene);
  if (c.scene == Scene::chain) out << " of " << c.bodies << (c.kick != 0.0 ? " kick=" + brief(c.kick) : "");
  out << ' ' << name(c.pulse) << ' ' << name(c.directivity) << ' ';
  // The scene's numbers: those it requires, and the others where they are not the default.
  for (const CaseField& f : kCaseFields)
    if (f.text && used_by(f, c))
      out << ' ' << f.name << '=' << c.*f.text;
    else if (used_by(f, c) && (f.use != FieldUse::chain || f.yielding) && (f.required || f.get(c) != f.get(Case{})))
      out << ' ' << f.name << '=' << brief(f.get(c));
  out << '\n';
  if (const std::string source = w_p_source(c); !source.empty())
    out << "record   peak " << brief(c.samples->peak) << ", mean period T_m " << brief(c.samples->t_m) << " s; w_p "
        << brief(c.w_p) << " (T_p " << brief(2.0 * std::numbers::pi / c.w_p) << " s, "
        << (source == "given" ? "given" : "2 pi / T_m") << "), a_p " << brief(c.a_p) << '\n';
  out << "solver   " << row.solver << "  (";
  // The named values as "name value, ...": a line to read; --json has them as an object.
  const char* sep = "";
  const auto settings = nlohmann::ordered_json::parse(row.settings);
  for (const auto& [key, value] : settings.items()) {
    out << sep << key << ' ' << (value.is_string() ? value.get<std::string>() : value.dump());
    sep = ", ";
  }
  out << ")\n";
  out << "status   " << name(r.status) << (r.message.empty() ? "" : ": " + r.message) << '\n';
  if (r.resolved) {
    out << "verdict  "
        << (*r.resolved ? "resolved (no criterion of kit/verdict.hpp failed, error estimate within the target)"
                        : "UNRESOLVED, do not trust this Pi1: " + r.unresolved)
        << '\n';
  }
  print_estimate(out, row);
  out << "Pi1      " << brief(r.pi1) << "  (no contact " << brief(row.pi1_no_contact)
      << "), at t = " << brief(r.t_max) << '\n';
  out << "impacts  " << r.impacts << ", contact phases " << r.contact_phases << ", steps/events " << r.steps << '\n';
  const double gap = min_gap_ratio(row);
  out << "min gap  " << (std::isinf(gap) ? std::string("never below zero") : brief(gap) + " a_p/w_p^2") << '\n';
  if (std::isfinite(row.wh)) {
    out << "step     w_max h = " << brief(row.wh);
    // On a record: the step against the sampling interval, and the rule that set it if any.
    if (c.samples && std::isfinite(r.step))
      out << ", h = " << brief(r.step) << " s, h / DT = " << brief(h_over_dt(row)) << " (DT "
          << brief(c.samples->interval()) << " s"
          << (row.settings.find("\"steps_per_sample\"") != std::string::npos ? ", step rule record" : "") << ')';
    out << '\n';
  }
  if (std::isfinite(r.energy_excess)) out << "energy   largest excess " << brief(r.energy_excess) << " of the energy scale\n";
  out << "penetr.  " << brief(penetration(row)) << " a_p/w_p^2";
  if (std::isfinite(row.penetration_steps)) out << ", " << brief(row.penetration_steps) << " steps of travel (h max|g'|)";
  out << '\n';
  if (r.isolated_impacts > 0)
    out << "restit.  " << brief(r.restitution_low) << " to " << brief(r.restitution_high) << " over "
        << r.isolated_impacts << " isolated impacts (eps " << brief(c.eps) << ")\n";
  if (yields(c)) {
    out << "yield    mu " << brief(ductility(row)) << " (Pi1 / Pi_y0), residual " << brief(r.residual)
        << " a_p/w_p^2, hysteretic " << brief(r.hysteretic) << " of the input energy\n";
  }
  out << "time     " << brief(row.seconds) << " s\n";
  print_physical(out, row);
}

// A point of a buildings case set, solved by a solver of the scene (frontend/buildings_run.hpp).
int run_buildings_command(const CLI::App& command, const RunFlags& flags, const ChosenCase& chosen) {
  const auto given = [&](std::string_view flag) { return command.count(std::string(flag)) > 0; };
  SolverFlags solver_flags = flags.solver_flags;
  if (given("--k-contact"))
    apply_buildings_k_contact(chosen.building->scene, solver_flags, flags.k_contact, given("--stiffness"));
  const SolverInfo& solver = check_buildings_solver(solver_flags, given);
  for (std::string_view flag : {"--history", "--samples", "--target-error", "--monitor"})
    if (given(flag)) throw BadInput(std::string(flag) + ": not for the buildings scene (yet)");
  const BuildingsRun run = run_buildings(chosen, solver, solver_flags.settings);
  write_to_stdout([&](std::ostream& out) {
    if (flags.json)
      out << buildings_json(run).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    else
      print_buildings_summary(out, run);
  });
  return run.point.result.status == Status::ok ? 0 : 1;
}

}  // namespace

CLI::App* add_run_command(CLI::App& app, RunFlags& flags) {
  CLI::App* command = app.add_subcommand("run", "Solve one case and print Pi1 and the event counts");
  add_case_flags(*command, flags.case_flags);
  add_solver_flags(*command, flags.solver_flags);
  command->add_flag("--json", flags.json, "Print one JSON object instead of the summary");
  command->add_option("--history", flags.history,
                      "Write the time history as CSV (t,u1,u0,...,v...,g...,lambda...) to this file");
  command->add_option("--samples", flags.samples, "Samples of the time history (with --history)")
      ->capture_default_str();
  add_estimate_flags(*command, flags.estimate, false);
  command->add_option("--k-contact", flags.k_contact,
                      "Compliant: contact stiffness in N/m (linear element) or N/m^1.5 (Hertz family), for a case in "
                      "physical units; sets --stiffness's Pi term K");
  return command;
}

int run_command(const CLI::App& command, RunFlags flags) {
  const ChosenCase chosen = chosen_case_or_buildings(
      [&](std::string_view flag) { return command.count(std::string(flag)) > 0; }, flags.case_flags);
  if (chosen.building) return run_buildings_command(command, flags, chosen);
  check_estimate_flags(command, flags.estimate, false);
  const bool history = command.count("--history") > 0;
  if (command.count("--samples") && !history) throw BadInput("--samples: only used with --history");
  if (history) {
    check_samples(flags.samples, chosen.input);
    flags.solver_flags.settings.history_samples = flags.samples;
  }
  const bool k_contact = command.count("--k-contact") > 0;
  if (k_contact)
    apply_k_contact(chosen.input, flags.solver_flags.solver, flags.solver_flags.settings, flags.k_contact,
                    command.count("--stiffness") > 0);
  const SolverInfo& solver = checked_solver_k_contact(
      flags.solver_flags, [&](std::string_view flag) { return command.count(std::string(flag)) > 0; }, k_contact);
  check_step_bound(chosen.input, flags.solver_flags.settings);
  if (history) {
    std::vector<NamedFile> inputs = record_files(std::span<const Case>(&chosen.input, 1));
    if (!chosen.case_file.empty()) inputs.push_back({"--case-file", chosen.case_file});
    check_outputs_apart({{"--history", flags.history}}, inputs);
    check_output_target(flags.history, "--history");
  }

  // Without --monitor the one solve is monitored (sweep.hpp, run_point's monitor_timed).
  const bool second_pass = flags.solver_flags.settings.monitor;
  Settings settings = flags.solver_flags.settings;
  settings.monitor = true;
  Row row = run_point(chosen.input, chosen.point, solver, settings, 1, nullptr, !second_pass, flags.estimate);
  add_body_peaks(row, solver, settings);
  if (history)
    write_atomically(flags.history, [&](std::ostream& out) { write_history(out, row.result.history, row.input); });

  write_to_stdout([&](std::ostream& out) {
    if (flags.json)
      out << row_json(row, chosen).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    else
      print_summary(out, row);
  });
  // Also where a script that reads only stdout's Pi1 leaves its log: status ok says the run
  // finished, not that it resolved what it solved.
  if (row.result.resolved == false)
    std::cerr << "poundbench: warning: the run did not resolve what it solved (" << clip(row.result.unresolved, 200)
              << "): its Pi1 is not to be trusted\n";
  return row.result.status == Status::ok ? 0 : 1;
}

}  // namespace pb::app
