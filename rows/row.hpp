#pragma once
// One result row of a sweep: the case that was solved, which solver and settings solved
// it, what came out, and how long the solve took. Rows are written as CSV, one line per
// row, with numbers printed so that they read back to the same double.
//
// Columns (csv_header()): the case's (cases/fields.hpp, cases/physical.hpp) and the result's
// (rows/result_fields.hpp, which says what each holds and where its column sits), in the order
//   family, point, scene, pulse, directivity, pi2, pi3, eps, pi5, pi6, pi7, pi8, xi,
//   n_free, a_p, w_p, solver, variant, settings, status, pi1, pi1_no_contact, impacts,
//   contact_phases, steps, min_gap, seconds, cpu_seconds, message, bodies, kick, wh,
//   energy_excess, penetration, isolated_impacts, restitution_low, restitution_high,
//   penetration_steps, cpu_seconds_low, cpu_seconds_high, repetitions, cycles, mp_gamma,
//   mp_nu, record, resolved, unresolved, pi_y0, pi_y1, pi_y2, pi_y, alpha, mu, residual, hysteretic,
//   t0, ... (the physical values and results), solve_seconds, startup_seconds, h_over_dt,
//   error_estimate, error_estimate_velocity
// A column that does not apply (a body the scene lacks, a pulse's shape, yielding's fields for
// an elastic case) and a NaN are empty fields. The columns after message came later; they are
// appended so that scripts reading columns by position keep working.
//
// Timing: the solve alone, with the monitor off, the clocks' own cost taken off (about 0.37 us
// of CPU: the thread's CPU clock is a system call; sweep/stopwatch.hpp), repeated
// (sweep/sweep.hpp: up to the run's repetitions, fewer once a point's solves have spent
// kRepetitionBudget = 10 ms of CPU time, at least one). seconds and cpu_seconds are the
// medians over the repetitions, cpu_seconds_low and cpu_seconds_high the fastest and the
// slowest, repetitions how many there were. A file from before repetitions lacks the last
// three: read back, low and high are NaN and repetitions 1.

#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cases/case.hpp"
#include "kit/solver.hpp"

namespace pb {

struct Row {
  Case input;              // the case that was solved
  std::size_t point = 0;   // its index in the sweep's list of cases
  std::size_t run = 0;     // the index of its solver and settings in the sweep's runs (not a column)
  std::string solver;      // SolverInfo::name
  std::string variant;     // Settings::variant as given (empty: the solver's default)
  std::string settings;    // SolverInfo::describe(settings): a JSON object of named values
  Result result;
  double pi1_no_contact = std::numeric_limits<double>::quiet_NaN();
  // With every contact removed (kit/separation.hpp), over a_p / w_p^2 as Pi1: the gap that
  // avoids pounding under the load as given and reversed, each rule's gap, and every body's
  // peak (body 0 first). NaN and empty where not computed (a chain, or a file from before).
  double separation = std::numeric_limits<double>::quiet_NaN();
  double separation_reversed = std::numeric_limits<double>::quiet_NaN();
  double separation_abs = std::numeric_limits<double>::quiet_NaN();
  double separation_srss = std::numeric_limits<double>::quiet_NaN();
  double separation_ddc = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> peaks_no_contact;
  // Every body's peak |u| with contact, over a_p / w_p^2, body 0 first (its Pi1), then the others
  // left to right; `run` alone measures it (add_body_peaks, sweep/sweep.hpp): empty in a sweep.
  std::vector<double> peaks;
  double length_scale = std::numeric_limits<double>::quiet_NaN();  // System::length_scale()
  double wh = std::numeric_limits<double>::quiet_NaN();  // w_max h of a time-stepper's step
  double penetration_steps = std::numeric_limits<double>::quiet_NaN();  // of the result (a column)
  double seconds = 0.0;      // wall time of the solve alone (the median repetition)
  double cpu_seconds = 0.0;  // CPU time of the solve alone, on its thread and in the processes it ran (the
                             // external solver's program; Result::child_cpu_seconds): robust to load; the median
  double cpu_seconds_low = std::numeric_limits<double>::quiet_NaN();   // the fastest repetition's
  double cpu_seconds_high = std::numeric_limits<double>::quiet_NaN();  // the slowest repetition's
  int repetitions = 1;  // timed solves
};

// The columns of the timing: the only ones that differ between two runs of one sweep.
inline constexpr std::array<std::string_view, 5> kTimingColumns = {"seconds", "cpu_seconds", "cpu_seconds_low",
                                                                   "cpu_seconds_high", "repetitions"};
// Empties them: NaN times and one repetition (a baseline's rows, two sweeps compared).
void clear_timing(Row& row);

// Result::min_gap over the length scale: dimensionless like Pi3 (infinite if no contact).
double min_gap_ratio(const Row& row);

// The deepest penetration over a_p / w_p^2, the one length scale of Pi3, Pi1 and min_gap
// (0 if none). It was over delta, or over a_p / w_p^2 where delta = 0: one overlap of
// Moreau-Jean at N = 16 read 0.138 at Pi3 = 0 and 138 094 at Pi3 = 1e-6 (issue 32).
double penetration(const Row& row);

// A record's step over its sampling interval, h / DT (the column h_over_dt); NaN for a pulse.
double h_over_dt(const Row& row);

// Body 0's ductility demand mu = max |u0| / u_y0: Pi1 over its Pi_y (NaN where body 0 does
// not yield or Pi1 is not known).
double ductility(const Row& row);

// The deepest penetration over one step of travel at the run's fastest gap rate,
// Result::step times Result::gap_rate_max: at most 1 for a velocity-level scheme. NaN
// without a fixed step or a measured rate (the reference, monitor off).
double penetration_steps(const Result& r);

// What a row must be, whether it was just solved or read back from a file: "" when it
// is, otherwise the column and why not ("pi1: ..."). A row with status ok has a finite
// Pi1 >= 0; counts are >= 0; timing columns are >= 0 and finite, or missing (NaN, as a
// baseline leaves them). run_point turns a solver's result that breaks this into a failed
// row, and the readers (rows/row_read.hpp) refuse a record that breaks it, so a resumed
// sweep or a comparison never takes a damaged row for a result.
std::string row_problem(const Row& row);

// The physics of a case as text (scene, pulse, directivity, every number the scene uses):
// equal exactly when two rows are of the same case. Matches rows with stored ones.
std::string case_key(const Case& c);
// Result::resolved as the `resolved` column writes it ("true", "false", "" when not judged),
// and back (nullopt: none of these).
std::string_view resolved_text(const std::optional<bool>& resolved);
std::optional<std::optional<bool>> parse_resolved(std::string_view text);
// A CSV field, quoted as RFC 4180 asks only when it holds a comma, a quote, CR or LF.
std::string csv_field(std::string_view text);

// Without a line end; write_csv ends every line with '\n'.
std::string csv_header();
std::string csv_line(const Row& row);
void write_csv(std::ostream& out, std::span<const Row> rows);

}  // namespace pb
