#pragma once
// Accuracy regression baselines: the rows of a case set through the reference and through
// every setting of a settings list, stored in the repository, and the comparison that
// catches any change in a solver's Pi1.
//
// A baseline file is CSV as write_csv writes it, with empty timing columns (they differ
// every run), after comment lines that say what made it:
//
//   # poundbench baseline
//   # cases: ../../cases/sets/smoke.toml          relative to the baseline file
//   # settings: ../../cases/settings/baseline.toml   or "none": the reference alone
//   # commit: 1a2b3c4 ...                         provenance, for people: not checked
//
// Two comparisons (compare_rows):
//   same_setting  each row against the stored row of the same solver, variant, settings and
//                 case, within the solver's baseline_tolerance: the regression check;
//   reference     each row, of any solver, against the stored reference row of the same
//                 case: how far another solver's rows (a downstream project's) are from it.
// Cases are matched by their physics (scene, pulse, directivity, Pi terms, xi, n_free,
// a_p, w_p, bodies, kick), never by point index or family label.

#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cases/case.hpp"
#include "rows/row.hpp"
#include "studies/settings_list.hpp"
#include "sweep/sweep.hpp"

namespace pb {

// The relative Pi1 difference a solver's stored results may move by before the check fails:
// a stated margin above the run-to-run and compiler noise measured for it (tests/baseline_test.cpp).
double baseline_tolerance(std::string_view solver);

// The rows a baseline stores: the case set through the reference at its default settings
// (Settings{}), then through every run of the list (none when list is null), each run in
// point order; timing columns cleared. Empty if cancelled.
std::vector<Row> run_baseline(std::span<const Case> cases, const SettingsList* list, const SweepOptions& options);

// The provenance comment lines of a baseline file (without '#').
struct BaselineHeader {
  std::string cases;     // path of the case set, relative to the baseline file
  std::string settings;  // path of the settings list, relative to the baseline file; "" = none
  std::vector<std::string> notes;  // further "key: value" lines (commit, compiler, date)
};
std::vector<std::string> header_lines(const BaselineHeader& h);
// Throws RowReadError (rows/row_read.hpp) naming the file when a line is missing.
BaselineHeader parse_header(std::span<const std::string> comments, std::string_view source);

enum class Match { same_setting, reference };

// One line of a comparison: the rows of one family and one solver setting.
struct Comparison {
  std::string family, solver, variant, settings;
  double tolerance = 0.0;
  std::size_t compared = 0;   // rows with a stored counterpart
  std::size_t failed = 0;     // of those: status differs, or |Pi1 - stored| > tolerance |stored|
  std::size_t unmatched = 0;  // rows with no stored counterpart
  std::size_t missing = 0;    // stored rows of this setting with no row (same_setting only)
  double max_difference = 0.0;  // largest relative Pi1 difference (inf: a status differs)
  std::size_t worst_point = 0;  // the point (of the rows) where it is

  // The check: nothing failed; same_setting also needs every row and stored row matched.
  bool passed(Match m) const;
};

// tolerance: NaN takes baseline_tolerance(row's solver).
std::vector<Comparison> compare_rows(std::span<const Row> rows, std::span<const Row> stored, Match match,
                                     double tolerance = std::numeric_limits<double>::quiet_NaN());

// A comparison as text: one aligned line per Comparison, with a header.
std::string comparison_table(std::span<const Comparison> table, Match match);

}  // namespace pb
