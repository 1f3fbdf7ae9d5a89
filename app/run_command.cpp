#include "app/run_command.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/errors.hpp"
#include "app/output_files.hpp"
#include "cases/fields.hpp"
#include "sweep/sweep.hpp"

namespace pb::app {

namespace {

// The paper's labels of the bodies, left to right (body 0 is the reported one).
// A chain's bodies are numbered from its left end.
std::vector<std::string> body_labels(const Case& c) {
  switch (c.scene) {
    case Scene::wall: return {"0"};
    case Scene::pair: return {"1", "0"};
    case Scene::row3: return {"1", "0", "2"};
    case Scene::chain: {
      std::vector<std::string> labels;
      for (int i = 0; i < c.bodies; ++i) labels.push_back(std::to_string(i));
      return labels;
    }
  }
  return {};
}

void write_history(std::ostream& out, const History& h, const Case& c) {
  const Scene scene = c.scene;
  const std::vector<std::string> bodies = body_labels(c);
  const int contacts = contact_count(c);
  // A run that failed before its first sample leaves an empty history: header only.
  const bool empty = h.n_bodies == 0 && h.data.empty();
  if (!empty && (h.n_bodies != static_cast<int>(bodies.size()) || h.n_contacts != contacts))
    throw std::runtime_error("history: the solver returned " + std::to_string(h.n_bodies) + " bodies and " +
                             std::to_string(h.n_contacts) + " contacts for scene " + std::string(name(scene)));
  out << 't';
  for (const char* quantity : {"u", "v"})
    for (const std::string& body : bodies) out << ',' << quantity << body;
  for (const char* quantity : {"g", "lambda"})
    for (int j = 1; j <= contacts; ++j) out << ',' << quantity << j;
  out << '\n';
  const auto width = static_cast<std::size_t>(h.row_size());
  for (std::size_t r = 0; r < h.rows(); ++r) {
    for (std::size_t k = 0; k < width; ++k) out << (k ? "," : "") << format_number(h.data[r * width + k]);
    out << '\n';
  }
}

nlohmann::ordered_json case_json(const Case& c) {
  nlohmann::ordered_json j;
  j["family"] = c.family;
  j["scene"] = name(c.scene);
  j["pulse"] = name(c.pulse);
  j["directivity"] = name(c.directivity);
  for (const CaseField& field : kCaseFields) {
    if (!used_by(field, c.scene)) continue;
    if (field.integer)
      j[std::string(field.name)] = c.*field.integer;
    else
      j[std::string(field.name)] = c.*field.number;
  }
  return j;
}

// NaN and infinity have no JSON spelling; null says "no value".
nlohmann::ordered_json number_or_null(double x) {
  return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json row_json(const Row& row, const ChosenCase& chosen) {
  const Result& r = row.result;
  nlohmann::ordered_json j;
  j["status"] = name(r.status);
  j["message"] = r.message;
  j["pi1"] = number_or_null(r.pi1);
  j["pi1_no_contact"] = number_or_null(row.pi1_no_contact);
  j["t_max"] = number_or_null(r.t_max);
  j["impacts"] = r.impacts;
  j["contact_phases"] = r.contact_phases;
  j["steps"] = r.steps;
  j["min_gap"] = number_or_null(min_gap_ratio(row));
  j["seconds"] = row.seconds;
  j["wh"] = number_or_null(row.wh);
  j["energy_excess"] = number_or_null(r.energy_excess);
  j["penetration"] = number_or_null(penetration(row));
  j["isolated_impacts"] = r.isolated_impacts;
  j["restitution_low"] = number_or_null(r.restitution_low);
  j["restitution_high"] = number_or_null(r.restitution_high);
  j["solver"] = row.solver;
  j["variant"] = row.variant;
  j["settings"] = nlohmann::json::parse(row.settings);
  if (!chosen.case_file.empty()) {
    j["case_file"] = chosen.case_file;
    j["point"] = chosen.point;
  }
  j.update(case_json(row.input));
  return j;
}

// Six significant digits: enough to read; --json has every digit.
std::string brief(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

void print_summary(std::ostream& out, const Row& row) {
  const Case& c = row.input;
  const Result& r = row.result;
  out << name(c.scene);
  if (c.scene == Scene::chain) out << " of " << c.bodies << (c.kick != 0.0 ? " kick=" + brief(c.kick) : "");
  out << ' ' << name(c.pulse) << ' ' << name(c.directivity) << ' ';
  // The scene's numbers: those it requires, and the others where they are not the default.
  for (const CaseField& f : kCaseFields)
    if (used_by(f, c.scene) && f.use != FieldUse::chain && (f.required || f.get(c) != f.get(Case{})))
      out << ' ' << f.name << '=' << brief(f.get(c));
  out << '\n';
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
  out << "Pi1      " << brief(r.pi1) << "  (no contact " << brief(row.pi1_no_contact)
      << "), at t = " << brief(r.t_max) << '\n';
  out << "impacts  " << r.impacts << ", contact phases " << r.contact_phases << ", steps/events " << r.steps << '\n';
  const double gap = min_gap_ratio(row);
  out << "min gap  " << (std::isinf(gap) ? std::string("never below zero") : brief(gap) + " a_p/w_p^2") << '\n';
  if (std::isfinite(row.wh)) out << "step     w_max h = " << brief(row.wh) << '\n';
  if (std::isfinite(r.energy_excess)) out << "energy   largest excess " << brief(r.energy_excess) << " of the energy scale\n";
  out << "penetr.  " << brief(penetration(row)) << (c.pi3 > 0.0 ? " of delta\n" : " a_p/w_p^2\n");
  if (r.isolated_impacts > 0)
    out << "restit.  " << brief(r.restitution_low) << " to " << brief(r.restitution_high) << " over "
        << r.isolated_impacts << " isolated impacts (eps " << brief(c.eps) << ")\n";
  out << "time     " << brief(row.seconds) << " s\n";
}

// A history is held in memory, then written as CSV (about 20 bytes a value), so its size
// is bounded before the run: 1e6 samples resolve a run of the longest allowed length
// (1e6 shortest periods, cases/case.hpp) to one sample a period, finer than any plot
// or check needs; and 2e7 values (160 MB held, about 400 MB written) bound the history
// of a long chain, whose rows have 4 N - 1 values. --samples 1e8 of a pair asked for 5.6 GB.
constexpr long long kMaxHistorySamples = 1'000'000;
constexpr long long kMaxHistoryValues = 20'000'000;

void check_samples(int samples, const Case& c) {
  if (samples < 2) throw BadInput("--samples: must be >= 2");
  if (samples > kMaxHistorySamples)
    throw BadInput("--samples: must be <= " + std::to_string(kMaxHistorySamples));
  const long long row = 1 + 2LL * body_count(c) + 2LL * contact_count(c);
  if (samples * row > kMaxHistoryValues)
    throw BadInput("--samples: at most " + std::to_string(kMaxHistoryValues / row) + " for this scene (" +
                   std::to_string(row) + " values a sample, " + std::to_string(kMaxHistoryValues) +
                   " values of history at most)");
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
  return command;
}

int run_command(const CLI::App& command, RunFlags flags) {
  const ChosenCase chosen = chosen_case(command, flags.case_flags);
  const bool history = command.count("--history") > 0;
  if (command.count("--samples") && !history) throw BadInput("--samples: only used with --history");
  if (history) {
    check_samples(flags.samples, chosen.input);
    flags.solver_flags.settings.history_samples = flags.samples;
  }
  const SolverInfo& solver = checked_solver(flags.solver_flags);
  if (history) check_output_target(flags.history, "--history");

  const Row row = run_point(chosen.input, chosen.point, solver, flags.solver_flags.settings);
  if (history)
    write_atomically(flags.history, [&](std::ostream& out) { write_history(out, row.result.history, row.input); });

  write_to_stdout([&](std::ostream& out) {
    if (flags.json)
      out << row_json(row, chosen).dump() << '\n';
    else
      print_summary(out, row);
  });
  return row.result.status == Status::ok ? 0 : 1;
}

}  // namespace pb::app
