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
// a_p, w_p, bodies, kick), never by point index or family label: the names and whole numbers
// exactly, every other number within kCaseMatchTolerance (relative), so that rows another
// program wrote to 6 significant digits find their stored case. A row that matches none
// names the nearest stored case of its scene, pulse and directivity, and how far it is.

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

// Two cases are the same when their names and whole numbers are equal and every other number
// agrees to this, relative (|a - b| <= tol max(|a|, |b|)): a number written to 6 significant
// digits is within 5e-6 of the one it was written from, and the closest two cases of a
// shipped set differ by 2e-2 (the paper set's 200-point Pi2 grids over two decades). Where
// two stored cases are both within it, the nearer one is the match.
inline constexpr double kCaseMatchTolerance = 1e-5;

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

// A row that matched no stored case, and the stored case nearest to it.
struct Unmatched {
  std::size_t point = 0;  // the row's point
  std::string row_case;   // its case: "pair sine normal pi2=0.5 pi3=0.5 ..."
  std::string nearest;    // "family f point 17: pi2=0.501187 (2.4e-03 apart)", or why there is none
};

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
  std::vector<Unmatched> unmatched_rows;  // the first kNamedUnmatched of the unmatched rows

  // The check: nothing failed, something was compared, and every row matched a stored case
  // (unless allow_unmatched); same_setting also needs every stored row of the setting matched.
  bool passed(Match m, bool allow_unmatched = false) const;
};

// Unmatched rows named per comparison line, with their nearest stored case (the rest are counted).
inline constexpr std::size_t kNamedUnmatched = 3;

// tolerance: NaN takes baseline_tolerance(row's solver).
std::vector<Comparison> compare_rows(std::span<const Row> rows, std::span<const Row> stored, Match match,
                                     double tolerance = std::numeric_limits<double>::quiet_NaN());

// A comparison as text: one aligned line per Comparison, with a header, each setting
// whole (its column as wide as the widest); then a line per named unmatched row.
std::string comparison_table(std::span<const Comparison> table, Match match, bool allow_unmatched = false);

// A comparison line's setting as the table prints it: solver, variant, settings.
std::string setting_text(const Comparison& c);

}  // namespace pb
