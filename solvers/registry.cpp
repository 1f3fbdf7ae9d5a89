#include <array>

#include "solvers/event_driven/event_driven.hpp"
#include "solvers/solver.hpp"

namespace pb {

std::string_view name(Status s) {
  switch (s) {
    case Status::ok: return "ok";
    case Status::diverged: return "diverged";
    case Status::nan: return "nan";
    case Status::step_cap: return "step_cap";
    case Status::timeout: return "timeout";
    case Status::failed: return "failed";
  }
  return "?";
}

namespace {

const std::array kSolvers = {
    SolverInfo{"event-driven", "exact between events, Poisson impacts (the reference)", &event_driven::solve,
               &event_driven::describe, &event_driven::check},
};

}  // namespace

std::span<const SolverInfo> solvers() { return kSolvers; }

const SolverInfo* find_solver(std::string_view solver_name) {
  for (const SolverInfo& s : kSolvers)
    if (s.name == solver_name) return &s;
  return nullptr;
}

}  // namespace pb
