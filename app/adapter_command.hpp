#pragma once
// `poundbench adapter --solver NAME [solver flags]`: poundbench as an external program. It
// reads one case document on stdin, solves it with a solver of its own registry and writes
// the answer document on stdout (docs/external.md), so that
//
//   poundbench spectrum SET --solver external --command "poundbench adapter --solver moreau-jean"
//
// runs the protocol end to end with a solver whose in-process answer is known: the Pi1 is
// the same bit for bit, and the difference in time is the protocol's cost per point.
//
// The document gives the run's step (steps_per_period, else step as --wh), step cap, time
// limit, history and monitor; the flags give the solver, its variant and its own settings.
// A bad flag or a bad document is a bad input (exit 2, one line on stderr, which the
// external solver quotes in its row); an answer, whatever its status, exits 0.

#include <CLI/CLI.hpp>

#include "frontend/solver_flags.hpp"

namespace pb::app {

struct AdapterFlags {
  SolverFlags solver_flags;
};

CLI::App* add_adapter_command(CLI::App& app, AdapterFlags& flags);
int adapter_command(const CLI::App& command, const AdapterFlags& flags);

}  // namespace pb::app
