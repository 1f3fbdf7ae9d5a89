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

Summary summarize(std::span<const Row* const> rows, std::span<const double> reference) {
  Summary s;
  s.points = rows.size();
  std::vector<double> errors, cpu;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& row = *rows[i];
    cpu.push_back(row.cpu_seconds);
    if (row.result.status != Status::ok || !std::isfinite(row.result.pi1)) {
      ++s.failed;
      continue;
    }
    errors.push_back(std::abs(row.result.pi1 - reference[i]) / std::abs(reference[i]));
  }
  if (!errors.empty()) {
    s.err_median = percentile(errors, 50.0);
    s.err_p95 = percentile(errors, 95.0);
    s.err_max = *std::max_element(errors.begin(), errors.end());
  }
  if (!cpu.empty()) {
    s.cpu_median = percentile(cpu, 50.0);
    s.cpu_mean = std::accumulate(cpu.begin(), cpu.end(), 0.0) / static_cast<double>(cpu.size());
  }
  return s;
}

}  // namespace pb
