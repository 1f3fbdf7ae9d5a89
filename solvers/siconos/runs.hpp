#pragma once
// Internal to solvers/siconos/: the two integrations that siconos_solver.cpp dispatches to
// (no Siconos type appears here).

#include "solvers/siconos/siconos_solver.hpp"

namespace pb::siconos {

// TimeStepping with MoreauJeanOSI; the LCP by Lemke, or by enumeration. paths may be null.
Result run_time_stepping(const System& system, const Settings& settings, bool enumeration, LcpPaths* paths);

// EventDriven with LsodarOSI.
Result run_event_driven(const System& system, const Settings& settings);

}  // namespace pb::siconos
