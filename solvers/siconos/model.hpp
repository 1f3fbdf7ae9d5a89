#pragma once
// Internal to solvers/siconos/: the integrations that siconos_solver.cpp dispatches to
// (time_stepping.cpp, event_driven.cpp, newmark_alpha.cpp), and what they share on this side
// of engine.hpp: the case in Siconos' units, and the bookkeeping common to them.
//
// Units. Siconos is given the case in the pulse's units: lengths over L = a_p / w_p^2, times
// over 1 / w_p, masses as they are (m0 = 1). Pi1 does not depend on a_p and w_p, and Siconos'
// absolute tolerances (EventDriven's event tolerance, LSODAR's atol, the LCP solvers'
// acceptance tests) become tolerances relative to the pulse.

#include <string>
#include <vector>

#include "cases/system.hpp"
#include "solvers/siconos/engine.hpp"
#include "solvers/siconos/siconos_solver.hpp"
#include "kit/solver.hpp"

namespace pb::siconos {

// A time-stepping simulation with the integrator of `options`. paths (counted for
// MoreauJeanOSI only) may be null.
Result run_time_stepping(const System& system, const Settings& settings, const engine::StepperOptions& options,
                         LcpPaths* paths);

// EventDriven with NewMarkAlphaOSI.
Result run_newmark_alpha(const System& system, const Settings& settings);

// EventDriven with LsodarOSI.
Result run_event_driven(const System& system, const Settings& settings);

struct Units {
  double length = 1.0;  // a_p / w_p^2
  double time = 1.0;    // 1 / w_p
  double velocity() const { return length / time; }
};

Units units_of(const System& s);

// The model of s for engine.hpp, in Siconos' units; sample_step and t_end in System's.
engine::ModelSpec model_spec(const System& s, double sample_step, double t_end);

// A run's stop callback (engine::ModelSpec::stop, NewmarkAlphaRun's): one tick of the Deadline
// it is given (Settings::time_limit and Settings::stop).
bool deadline_passed(void* deadline);

// A Result that stops before a run: a status and why.
Result stopped(Status status, std::string message);

// Checks what Siconos is given: finite parameters (Siconos' LU factorisation prints a message
// of its own on a NaN) and a start state of one u and one v per body; "" when it is usable.
std::string check_system(const System& s);

// The state of a run in System's units, and the gaps and gap rates it gives.
struct State {
  std::vector<double> u, v;     // per body
  std::vector<double> g, rate;  // per contact
  explicit State(const System& s);
  // Reads the engine's state (Siconos' units) and updates the gaps.
  template <class Run>
  void read(const Run& run, const System& s, const Units& units) {
    run.state(u.data(), v.data());
    for (std::size_t i = 0; i < u.size(); ++i) {
      u[i] *= units.length;
      v[i] *= units.velocity();
    }
    update_gaps(s);
  }
  void update_gaps(const System& s);
  bool finite() const;
};

// One History row: t, u, v, g, and the contact forces (kit/solver.hpp).
void record(double t, const State& st, const std::vector<double>& force, std::vector<double>& out);

}  // namespace pb::siconos
