#include "app/adapter_command.hpp"

#include <iostream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "app/output_files.hpp"
#include "cases/fields.hpp"
#include "frontend/errors.hpp"
#include "solvers/external/protocol.hpp"

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
  const std::string input{std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
  if (std::cin.bad()) throw std::runtime_error("stdin: read failed");
  external::CaseRead read;
  try {
    read = external::read_case(input);
  } catch (const std::invalid_argument& e) {
    throw BadInput(std::string("stdin: ") + e.what());
  }
  SolverFlags solver_flags = flags.solver_flags;
  Settings& settings = solver_flags.settings;
  settings.steps = read.settings.steps;
  settings.wh = read.settings.wh;
  settings.step_cap = read.settings.step_cap;
  settings.time_limit = read.settings.time_limit;
  settings.history_samples = read.settings.history_samples;
  settings.monitor = read.settings.monitor;
  const SolverInfo& solver = checked_solver(solver_flags, command);
  const Result result = solver.solve(read.system, settings);
  write_to_stdout([&](std::ostream& out) { out << external::answer_document(result, read.system); });
  return 0;
}

}  // namespace pb::app
