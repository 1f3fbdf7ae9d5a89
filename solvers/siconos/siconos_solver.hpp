#pragma once
// Siconos (Debian's libsiconos-kernel-dev 4.4), the field's reference library for nonsmooth
// dynamics, as a pounding solver: the same scenes through its own integrators.
//
//   bodies    one LagrangianLinearTIDS per building (1x1 M, K, C), starting from
//             System::u_start, v_start; its external force -m a_g(t) is a load plugin.
//   contacts  one Interaction per contact: LagrangianLinearTIR y = C q + delta over the two
//             neighbours (C = [-1 1]; [1] against the wall), NewtonImpactNSL(eps).
//   units     Siconos sees every case in the pulse's units (lengths over a_p / w_p^2, times
//             over 1 / w_p), so that its absolute tolerances are relative to the pulse.
//   variants  moreau-jean-lemke (default) and moreau-jean-enum: TimeStepping with
//             MoreauJeanOSI(Settings::theta, Settings::gamma) and an LCP solved by Lemke or by
//             enumeration, h = time_step(system, settings, 64); event-driven-lsodar:
//             EventDriven with LsodarOSI at stated tolerances (times Settings::tol_scale);
//             Siconos' other nonsmooth integrators, each with its own simulation class and
//             its LCPs by Settings::lcp: schatzman-paoli, d1-minus-linear,
//             combined-projection, direct-projection (Settings::projection_tol), and two that
//             fail in Siconos 4.4 with a status naming the cause: bilbao (its free state
//             leaves out the external force) and newmark-alpha (EventDriven's Newton loop
//             never converges: NewMarkAlphaOSI negates the system's K and C in place).
//
// Every Siconos object stays in solvers/siconos/*.cpp; what each variant sets, what the runs
// measure, the LCP paths and the thread safety are in solvers/siconos/README.md.

#include <string>
#include <string_view>
#include <vector>

#include "kit/fixed_step.hpp"
#include "kit/solver.hpp"

namespace pb::siconos {

inline constexpr std::string_view kDefaultVariant = "moreau-jean-lemke";
inline constexpr long kDefaultEventCap = 1'000'000;   // event-driven: events, when Settings::step_cap is 0

// event-driven-lsodar: LSODAR's error control (itol = 1: scalar rtol and atol, on every
// state component in the pulse's units) at Settings::tol_scale = 1, and its output grid:
// the run stops every T_min / kOutputSteps, where Pi1 is refined by cubic Hermite
// interpolation of u0 between events (README).
inline constexpr double kRtol = 1e-10;
inline constexpr double kAtol = 1e-10;
inline constexpr int kOutputSteps = 256;

// The projections (combined-projection, direct-projection): the tolerance on a violated gap
// when Settings::projection_tol is 0 (pulse units: the prototype value), and the most
// projection iterations per step. Their MLCP is solved by enumeration (engine.cpp says why).
//
// Enumeration (a projection's MLCP, or an LCP's with Settings::lcp = enum) tries up to 2^n
// active sets of n contacts, each a dense solve: such a run refuses a system of more than
// kMaxEnumerationContacts contacts (2^12 = 4096 solves of 12 x 12 at worst), instead of
// hanging a sweep (measured: a stress sweep stuck in mlcp_enum on a 100-body chain). Time
// limits cannot reach inside one solve.
inline constexpr double kProjectionTol = 1e-10;  // check() names it: keep them equal
inline constexpr int kProjectionIterations = 20;
inline constexpr int kMaxEnumerationContacts = 12;

// newmark-alpha: NewMarkAlphaOSI's spectral radius at infinity, and when the run stops
// Siconos' Newton loop: after kNewtonOverrun times EventDriven's own iteration limit in one
// advance (past its limit Siconos only warns and iterates on, without end).
inline constexpr double kRhoInfinity = 0.7;
inline constexpr long kNewtonOverrun = 10;
Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);
std::vector<VariantInfo> variant_list();  // kDefaultVariant first

// Which path Siconos' dense LCP driver took on the steps of a time-stepping run. The driver
// is called on every step with a contact in the index set; it returns z = 0 without a solver
// when q >= 0, and z = -q / M without a solver when the LCP has one row.
struct LcpPaths {
  long calls = 0;     // steps with at least one active contact
  long trivial = 0;   // q >= 0: z = 0
  long one_row = 0;   // one active contact, q < 0: z = -q / M
  long solver = 0;    // Lemke or enumeration ran (the other calls)
  long written = 0;   // calls after which the solver's iteration counter had been written
};

// solve() for a MoreauJeanOSI variant, also counting the LCP paths (for tests).
Result solve_counting(const System& system, const Settings& settings, LcpPaths& paths);

// What the event-driven variant's integrators hold once its simulation is initialised, read
// back from Siconos (for tests: these must be the values this solver sets).
struct EventDrivenSetup {
  long itol = 0;
  double rtol = 0.0, atol = 0.0;
  double event_tolerance = 0.0;  // EventDriven::toleranceED(): |y| below it is a closed contact
  long itask = 0;                // LSODAR's itask (1: overshoot and interpolate to the output time)
};
EventDrivenSetup event_driven_setup(const System& system, const Settings& settings);

// What MoreauJeanOSI holds once a time-stepping simulation is initialised (for tests).
struct MoreauJeanSetup {
  double theta = 0.0, gamma = 0.0;
  bool use_gamma = false;
  double activation_threshold = 0.0;  // a contact is active when y + gamma h y' <= this
};
MoreauJeanSetup moreau_jean_setup(const System& system, const Settings& settings);

}  // namespace pb::siconos
