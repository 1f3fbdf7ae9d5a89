#pragma once
// The event-driven reference solver: exact between events, Poisson impacts, persistent
// contact and detachment. The derivation is in solvers/event_driven/DERIVATION.md.

#include <string>
#include <string_view>
#include <vector>

#include "kit/separation.hpp"
#include "kit/solver.hpp"

namespace pb::event_driven {

// Settings::variant that solves long runs of both LCPs by Lemke's method first: slower,
// and there to check the default's (the empty name's) fast paths against it.
inline constexpr std::string_view kLemkeVariant = "lemke";

Result solve(const System& system, const Settings& settings);
std::string describe(const Settings& settings);
std::string check(const Settings& settings);
std::vector<VariantInfo> variant_list();  // the default (no name), then kLemkeVariant

// Pi1 of body 0 with every contact removed: a damped oscillator under the pulse, exact.
// Only the time limit and stop flag of `limits` are used.
double no_contact_pi1(const System& system, const Settings& limits = {});

// The motion of every body with every contact removed, exact (kit/separation.hpp): the gap
// that avoids pounding. Only the time limit and stop flag of `limits` are used.
FreeMotion free_motion(const System& system, const Settings& limits = {});

// Settings::tol_scale multiplies tolerances of 1e-10 (gaps) to 1e-7 (speeds) relative to
// the pulse's scales: below 1e-5 the gap tolerance would be under double precision's
// round-off of the displacements it compares (1e-15 relative); above 1e4 the speed below
// which an approach counts as plastic (1e-7 tol_scale a_p / w_p) would pass
// kRestitutionFloor, where impacts are measured.
inline constexpr double kMinTolScale = 1e-5;
inline constexpr double kMaxTolScale = 1e4;
// A run is `ok` only when its answer is one: Pi1 finite, no gap below kPenetrationCheck
// closure tolerances, the energy balance within kEnergyCheck (times tol_scale when that is
// > 1) of System::energy_scale(). Beyond these the answer is wrong, not merely rounded
// (measured on the stress set: at most 1.0005 closure tolerances and 1e-13 of the scale).
inline constexpr double kPenetrationCheck = 10.0;
inline constexpr double kEnergyCheck = 1e-9;
// Turns an `ok` result that fails those checks into the status naming the first that failed.
void check_result(const System& system, double tol_scale, Result& result);

namespace detail {
// For tests: solve() with every contact searched again at every event, as before the
// searches were kept across events (DERIVATION.md §9).
Result solve_searching_every_contact(const System& system, const Settings& settings);
// solve() with every body advanced, and the whole frame rebuilt, at every event, as before
// an event rebuilt only the clusters it changed (DERIVATION.md §9).
Result solve_rebuilding_every_body(const System& system, const Settings& settings);
// solve() and free_motion() with every sample of a record taken as an event, searched in
// full, as before the recurrence (DERIVATION.md §11) took the intervals it proves empty.
Result solve_searching_every_sample(const System& system, const Settings& settings);
FreeMotion free_motion_searching_every_sample(const System& system, const Settings& limits = {});
}  // namespace detail

}  // namespace pb::event_driven
