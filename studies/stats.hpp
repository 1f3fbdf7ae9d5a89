#pragma once
// Accuracy and cost of one solver setting over a family of points, against a reference.

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "rows/row.hpp"

namespace pb {

// The p-th percentile (0 <= p <= 100) by linear interpolation between order statistics
// (numpy's default); NaN for an empty sample.
double percentile(std::vector<double> sample, double p);

struct Summary {
  std::size_t points = 0;  // rows summarised
  std::size_t failed = 0;  // status other than ok, or a Pi1 that is not finite
  // Relative Pi1 error |Pi1 - Pi1_ref| / Pi1_ref over the runs that did not fail.
  double err_median = std::numeric_limits<double>::quiet_NaN();
  double err_p95 = std::numeric_limits<double>::quiet_NaN();
  double err_max = std::numeric_limits<double>::quiet_NaN();
  // CPU seconds per run (the solve alone), over every run.
  double cpu_median = std::numeric_limits<double>::quiet_NaN();
  double cpu_mean = std::numeric_limits<double>::quiet_NaN();
};

// rows[i] is compared with reference[i] (same point); both spans have the same length.
Summary summarize(std::span<const Row* const> rows, std::span<const double> reference);

}  // namespace pb
