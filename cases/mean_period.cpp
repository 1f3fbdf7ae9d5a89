#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "cases/record.hpp"

namespace pb {

namespace {

// Within this of the mean spacing, samples count as evenly spaced and are taken as they are
// (every AT2 record, and a CSV written at a fixed step, up to its decimal rounding).
constexpr double kEvenSpacing = 1e-6;

}  // namespace

double mean_period(const std::vector<double>& t, const std::vector<double>& a) {
  const std::size_t n = t.size();
  if (n < 2 || a.size() != n) return std::numeric_limits<double>::quiet_NaN();
  // The record on an even grid of its mean spacing, linear between its samples (a record
  // moved in time has the same Fourier amplitudes: its first sample is the grid's start).
  const double dt = (t.back() - t.front()) / static_cast<double>(n - 1);
  bool even = true;
  for (std::size_t i = 1; i < n && even; ++i) even = std::abs(t[i] - t[i - 1] - dt) <= kEvenSpacing * dt;
  // Zero-padded to a power of two: an FFT of any length at N log N (a prime length would cost
  // N^2), and the record's integral sampled on a finer grid of frequencies, which T_m, a ratio
  // of sums over the band, does not depend on beyond that sampling.
  std::size_t size = 1;
  while (size < n) size *= 2;
  std::vector<double> even_a(size, 0.0);
  for (std::size_t i = 0, j = 0; i < n; ++i) {
    if (even) {
      even_a[i] = a[i];
      continue;
    }
    const double at = t.front() + dt * static_cast<double>(i);
    while (j + 2 < n && t[j + 1] <= at) ++j;
    const double x = std::clamp((at - t[j]) / (t[j + 1] - t[j]), 0.0, 1.0);
    even_a[i] = a[j] + (a[j + 1] - a[j]) * x;
  }
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, even_a);
  const double df = 1.0 / (static_cast<double>(size) * dt);
  double weighted = 0.0, total = 0.0;
  for (std::size_t k = 1; k <= size / 2; ++k) {
    const double f = static_cast<double>(k) * df;
    if (f < kMeanPeriodBand[0] || f > kMeanPeriodBand[1]) continue;
    const double c2 = std::norm(spectrum[k]);
    weighted += c2 / f;
    total += c2;
  }
  return total > 0.0 ? weighted / total : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace pb
