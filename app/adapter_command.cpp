#include "app/adapter_command.hpp"

#include <chrono>
#include <iostream>
#include <iterator>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "output/output_files.hpp"
#include "cases/fields.hpp"
#include "frontend/errors.hpp"
#include "programs/protocol.hpp"

namespace pb::app {

CLI::App* add_adapter_command(CLI::App& app, AdapterFlags& flags) {
  CLI::App* command = app.add_subcommand(
      "adapter", "Answer as an external program: read a case document on stdin, solve it, write the answer (docs/external.md)");
  add_solver_flags(*command, flags.solver_flags);
  return command;
}

int adapter_command(const CLI::App& command, const AdapterFlags& flags) {
  // What the document decides is not the flags' to give.
  for (const char* field : {"steps", "wh", "step_cap", "time_limit"})
    if (command.count(flag_of(field)))
      throw BadInput(flag_of(field) + ": the case document gives it (run the sweep with it instead)");
  // --persistent: a ready line, then an answer per case line (docs/external.md, "Persistent mode").
  const bool persistent = command.count("--persistent") > 0;
  SolverFlags base = flags.solver_flags;
  if (persistent) base.settings.variant.clear();
  const auto answer = [&](std::string_view input) {
    programs::CaseRead read;
    try {
      read = programs::read_case(input);
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("stdin: ") + e.what());
    }
    SolverFlags solver_flags = base;
    Settings& settings = solver_flags.settings;
    settings.steps = read.settings.steps;
    settings.wh = read.settings.wh;
    settings.step_cap = read.settings.step_cap;
    settings.time_limit = read.settings.time_limit;
    settings.history_samples = read.settings.history_samples;
    settings.monitor = read.settings.monitor;
    const SolverInfo& solver = checked_solver(solver_flags, command);
    const auto start = std::chrono::steady_clock::now();
    Result result = solver.solve(read.system, settings);
    result.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return programs::answer_document(result, read.system);
  };
  // stdin is read with no deadline of the adapter's own: the time limit is in the document, known
  // only once it has been read, so the program running the adapter bounds its whole run (the
  // external solver ends it at the point's limit plus kGraceSeconds). What the reading costs is
  // linear in the document (protocol.cpp's parse_object: no quadratic check of its keys).
  if (!persistent) {
    const std::string input{std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
    if (std::cin.bad()) throw std::runtime_error("stdin: read failed");
    const std::string text = answer(input);
    write_to_stdout([&](std::ostream& out) { out << text; });
    return 0;
  }
  std::cout << "{\"version\": 1, \"ready\": true}" << std::endl;
  for (std::string line; std::getline(std::cin, line);) {
    std::string text;
    try {
      text = answer(line);
    } catch (const BadInput& e) {  // this case's failed row; the next case is answered
      text = "{\"version\": 1, \"status\": \"failed\", \"message\": " + nlohmann::json(std::string(e.what())).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "}\n";
    }
    std::cout << text << std::flush;
  }
  return 0;
}

}  // namespace pb::app
