#include "studies/stats.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pb {

double percentile(std::vector<double> sample, double p) {
  if (sample.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(sample.begin(), sample.end());
  const double rank = p / 100.0 * static_cast<double>(sample.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(rank));
  const std::size_t hi = std::min(lo + 1, sample.size() - 1);
  return sample[lo] + (rank - static_cast<double>(lo)) * (sample[hi] - sample[lo]);
}

std::vector<std::string> families_in_order(std::span<const Case> cases) {
  std::vector<std::string> out;
  for (const Case& c : cases)
    if (std::find(out.begin(), out.end(), c.family) == out.end()) out.push_back(c.family);
  return out;
}

CpuCost cpu_cost(std::span<const Row* const> rows) {
  CpuCost c;
  if (rows.empty()) return c;
  std::vector<double> median, low, high;
  c.repetitions = rows.front()->repetitions;
  for (const Row* row : rows) {
    c.repetitions = std::min(c.repetitions, row->repetitions);
    median.push_back(row->cpu_seconds);
    low.push_back(std::isnan(row->cpu_seconds_low) ? row->cpu_seconds : row->cpu_seconds_low);
    high.push_back(std::isnan(row->cpu_seconds_high) ? row->cpu_seconds : row->cpu_seconds_high);
  }
  c.median = percentile(median, 50.0);
  c.mean = std::accumulate(median.begin(), median.end(), 0.0) / static_cast<double>(median.size());
  c.median_low = percentile(low, 50.0);
  c.median_high = percentile(high, 50.0);
  return c;
}

Summary summarize(std::span<const Row* const> rows, std::span<const double> reference) {
  Summary s;
  s.points = rows.size();
  std::vector<double> errors;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& row = *rows[i];
    if (row.result.status != Status::ok || !std::isfinite(row.result.pi1)) {
      ++s.failed;
      continue;
    }
    if (row.result.resolved == false) ++s.unresolved;
    if (!std::isfinite(reference[i])) continue;  // the reference's own failure: no error to measure
    errors.push_back(std::abs(row.result.pi1 - reference[i]) / std::abs(reference[i]));
  }
  if (!errors.empty()) {
    s.err_median = percentile(errors, 50.0);
    s.err_p95 = percentile(errors, 95.0);
    s.err_max = *std::max_element(errors.begin(), errors.end());
  }
  s.cpu = cpu_cost(rows);
  return s;
}

}  // namespace pb
