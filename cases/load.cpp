#include "cases/load.hpp"

#include <algorithm>

namespace pb {

double Sinusoid::integral(double a, double b) const {
  // s (cos wa - cos wb) / w + c (sin wb - sin wa) / w, with cos wa - cos wb =
  // 2 sin(w (a + b) / 2) sin(w (b - a) / 2) and sin wb - sin wa = 2 cos(w (a + b) / 2) sin(w (b - a) / 2).
  const double mid = 0.5 * w * (a + b), half = std::sin(0.5 * w * (b - a));
  return 2.0 * half * (s * std::sin(mid) + c * std::cos(mid)) / w;
}

double LoadPiece::accel(double t) const {
  double a = value + slope * (t - start);
  for (int j = 0; j < n_waves; ++j) a += waves[static_cast<std::size_t>(j)].at(t);
  return a;
}

double Pulse::mean(double t0, double t1) const {
  if (!paper()) {
    std::size_t i = locate(t0);
    return general_mean(t0, t1, i);
  }
  const double a = std::clamp(t0, 0.0, duration()), b = std::clamp(t1, 0.0, duration());
  if (b <= a) return 0.0;
  // Integral of sin(w t) over [a, b] is (cos wa - cos wb) / w = 2 sin(w (a + b) / 2) sin(w (b - a) / 2) / w;
  // of cos(w t), 2 cos(w (a + b) / 2) sin(w (b - a) / 2) / w: no cancellation for short steps.
  const double mid = 0.5 * w * (a + b), half = std::sin(0.5 * w * (b - a));
  const double integral = 2.0 * half * (shape == PulseShape::sine ? std::sin(mid) : std::cos(mid)) / w;
  return amplitude * integral / (t1 - t0);
}

double Pulse::sample(double t, double h) const {
  const double end = duration();
  return accel(std::abs(t - end) <= 1e-9 * std::max(h, end) ? end : t);
}

std::size_t Pulse::locate(double t, std::size_t hint) const {
  if (!record) return 0;
  const std::vector<double>& ts = record->t;
  const std::size_t last = ts.size() - 2;  // the last interval
  std::size_t i = std::min(hint, last);
  // A few steps from the hint (a time-stepper's next step is in the same interval or the
  // next one), then halving over what is left.
  if (t >= ts[i]) {
    for (int k = 0; k < 4; ++k) {
      if (i == last || t < ts[i + 1]) return i;
      ++i;
    }
    const auto it = std::upper_bound(ts.begin() + static_cast<std::ptrdiff_t>(i), ts.end(), t);
    return std::min(last, static_cast<std::size_t>(it - ts.begin()) - 1);
  }
  for (int k = 0; k < 4; ++k) {
    if (i == 0) return 0;
    --i;
    if (t >= ts[i]) return i;
  }
  const auto it = std::upper_bound(ts.begin(), ts.begin() + static_cast<std::ptrdiff_t>(i), t);
  return it == ts.begin() ? 0 : static_cast<std::size_t>(it - ts.begin()) - 1;
}

double Pulse::general_accel(double t, std::size_t i) const {
  if (record) {
    const std::vector<double>& ts = record->t;
    const std::vector<double>& as = record->a;
    if (t < ts.front() || t > ts.back()) return 0.0;
    const double x = (t - ts[i]) / (ts[i + 1] - ts[i]);
    return amplitude * (as[i] + (as[i + 1] - as[i]) * x);
  }
  if (t < 0.0 || t > length) return 0.0;
  double a = 0.0;
  for (int j = 0; j < n_waves; ++j) a += waves[static_cast<std::size_t>(j)].at(t);
  return a;
}

double Pulse::general_mean(double t0, double t1, std::size_t& i) const {
  if (record) {
    const std::vector<double>& ts = record->t;
    const std::vector<double>& as = record->a;
    const double a = std::max(t0, ts.front()), b = std::min(t1, ts.back());
    if (b <= a) return 0.0;
    i = locate(a, i);
    // The trapezoid of each interval's part in [a, b]: exact for a linear a_g.
    double sum = 0.0;
    for (;; ++i) {
      const double lo = std::max(a, ts[i]), hi = std::min(b, ts[i + 1]);
      const double slope = (as[i + 1] - as[i]) / (ts[i + 1] - ts[i]);
      const double f_lo = as[i] + slope * (lo - ts[i]), f_hi = as[i] + slope * (hi - ts[i]);
      sum += 0.5 * (hi - lo) * (f_lo + f_hi);
      if (i + 2 >= ts.size() || ts[i + 1] >= b) break;
    }
    return amplitude * sum / (t1 - t0);
  }
  const double a = std::clamp(t0, 0.0, length), b = std::clamp(t1, 0.0, length);
  if (b <= a) return 0.0;
  double sum = 0.0;
  for (int j = 0; j < n_waves; ++j) sum += waves[static_cast<std::size_t>(j)].integral(a, b);
  return sum / (t1 - t0);
}

LoadPiece Pulse::piece_at(double t, std::size_t i) const {
  LoadPiece p;
  const double inf = std::numeric_limits<double>::infinity();
  if (record) {
    const std::vector<double>& ts = record->t;
    const std::vector<double>& as = record->a;
    if (t < ts.front()) {
      // Zero before the first sample, from a finite start: the reference reads the piece's
      // value as value + slope (t - start), which an infinite start made NaN (0 inf), and a
      // record whose first sample came after t = 0 ended at once with status nan.
      p.start = std::min(t, 0.0);
      p.end = ts.front();
    } else if (t >= ts.back()) {
      p.start = ts.back();
    } else {
      p.start = ts[i];
      p.end = ts[i + 1];
      p.value = amplitude * as[i];
      p.slope = amplitude * ((as[i + 1] - as[i]) / (ts[i + 1] - ts[i]));
    }
    return p;
  }
  const double end = duration();
  if (t < 0.0) {
    p.start = -inf;
    p.end = 0.0;
  } else if (t >= end) {
    p.start = end;
  } else {
    p.start = 0.0;
    p.end = end;
    if (paper()) {
      p.n_waves = 1;
      p.waves[0] = {w, shape == PulseShape::sine ? amplitude : 0.0, shape == PulseShape::cosine ? amplitude : 0.0};
    } else {
      p.waves = waves;
      p.n_waves = n_waves;
    }
  }
  return p;
}

double makris_phase(int cycles) {
  // f(phi) = 2 cos phi - sin phi ((2n + 1) pi - 2 phi) falls from 2 at 0 to -2 n pi at pi/2
  // (f' = -cos phi ((2n + 1) pi - 2 phi) < 0): one root, by halving to the last bit.
  const double k = (2.0 * cycles + 1.0) * std::numbers::pi;
  double lo = 0.0, hi = 0.5 * std::numbers::pi;
  for (int it = 0; it < 200 && hi - lo > 0.0; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (2.0 * std::cos(mid) - std::sin(mid) * (k - 2.0 * mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Pulse make_pulse(const Case& c) {
  const double sign = c.directivity == Directivity::normal ? 1.0 : -1.0;
  Pulse p;
  p.shape = c.pulse;
  p.w = c.w_p;
  p.cycles = c.cycles;
  p.mp_gamma = c.mp_gamma;
  p.mp_nu = c.mp_nu;
  const double t_p = 2.0 * std::numbers::pi / c.w_p;
  const double a = sign * c.a_p;
  switch (c.pulse) {
    case PulseShape::sine:
    case PulseShape::cosine:
      p.amplitude = c.directivity == Directivity::normal ? c.a_p : -c.a_p;
      break;
    case PulseShape::makris_a:
      p.amplitude = a;
      p.waves[0] = {c.w_p, a, 0.0};
      p.n_waves = 1;
      p.length = t_p;
      break;
    case PulseShape::makris_b:
      p.amplitude = a;
      p.waves[0] = {c.w_p, 0.0, a};
      p.n_waves = 1;
      p.length = t_p;
      break;
    case PulseShape::makris_c: {
      // a cos(w t + phi) = a cos(phi) cos(w t) - a sin(phi) sin(w t)
      const double phi = makris_phase(c.cycles);
      p.amplitude = a;
      p.waves[0] = {c.w_p, -a * std::sin(phi), a * std::cos(phi)};
      p.n_waves = 1;
      p.length = (c.cycles + 0.5 - phi / std::numbers::pi) * t_p;
      break;
    }
    case PulseShape::mp: {
      // Velocity (A/2) (1 + cos(w tau / gamma)) cos(w tau + nu), tau = t - gamma T_p / 2 in
      // [-gamma T_p / 2, gamma T_p / 2], A = a_p / w_p. Its derivative, products expanded:
      //   a_g = -(a_p / 2) [sin(w tau + nu) + (1 + 1/gamma) / 2 sin(w (1 + 1/gamma) tau + nu)
      //                                   + (1 - 1/gamma) / 2 sin(w (1 - 1/gamma) tau + nu)]
      // and w_k tau = w_k t - (gamma + k) pi for w_k = w (1 + k / gamma), k = 0, 1, -1.
      const double g = c.mp_gamma, nu = c.mp_nu * std::numbers::pi / 180.0;
      const std::array<double, 3> ks = {0.0, 1.0, -1.0};
      const std::array<double, 3> amps = {-0.5 * a, -0.25 * a * (1.0 + 1.0 / g), -0.25 * a * (1.0 - 1.0 / g)};
      for (std::size_t j = 0; j < 3; ++j) {
        const double phase = nu - (g + ks[j]) * std::numbers::pi;
        p.waves[j] = {c.w_p * (1.0 + ks[j] / g), amps[j] * std::cos(phase), amps[j] * std::sin(phase)};
      }
      p.amplitude = a;
      p.n_waves = 3;
      p.length = g * t_p;
      break;
    }
    case PulseShape::record:
      p.amplitude = sign;
      p.record = c.samples;
      break;
  }
  return p;
}

}  // namespace pb
