#pragma once
// Accuracy and cost of one solver setting over a family of points, against a reference.

#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rows/row.hpp"

namespace pb {

// The p-th percentile (0 <= p <= 100) by linear interpolation between order statistics
// (numpy's default); NaN for an empty sample.
double percentile(std::vector<double> sample, double p);

// The families of a case list, each once, in the order of its first case.
std::vector<std::string> families_in_order(std::span<const Case> cases);

// What a setting's runs cost: CPU seconds per run, the solve alone (rows/row.hpp), over
// every run, failed or not.
struct CpuCost {
  double median = std::numeric_limits<double>::quiet_NaN();  // of the runs' cpu_seconds (each a median)
  double mean = std::numeric_limits<double>::quiet_NaN();
  // The spread of the median: the median over the runs of each one's fastest repetition,
  // and of each one's slowest. With a run's repetitions ranked from fastest to slowest,
  // these are the least and the largest, over ranks j, of the median over runs of the j-th:
  // the range of medians the study could have reported from one timing per run. A run
  // read from a file without the spread columns counts its one timing at both ends.
  double median_low = std::numeric_limits<double>::quiet_NaN();
  double median_high = std::numeric_limits<double>::quiet_NaN();
  int repetitions = 0;  // the fewest timed repetitions of a run (0: no runs)
};

CpuCost cpu_cost(std::span<const Row* const> rows);

struct Summary {
  std::size_t points = 0;  // rows summarised
  std::size_t failed = 0;  // status other than ok, or a Pi1 that is not finite
  // Finished runs that did not resolve what they solved (Result::resolved false,
  // kit/verdict.hpp); their errors count as every finished run's do.
  std::size_t unresolved = 0;
  // Relative Pi1 error |Pi1 - Pi1_ref| / Pi1_ref over the runs that did not fail, where the
  // reference has a Pi1.
  double err_median = std::numeric_limits<double>::quiet_NaN();
  double err_p95 = std::numeric_limits<double>::quiet_NaN();
  double err_max = std::numeric_limits<double>::quiet_NaN();
  CpuCost cpu;
};

// rows[i] is compared with reference[i] (same point); both spans have the same length.
Summary summarize(std::span<const Row* const> rows, std::span<const double> reference);

}  // namespace pb
