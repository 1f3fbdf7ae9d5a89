#include "kit/contact_elements/contact_law.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>

namespace pb::compliant {

std::string_view name(Model m) {
  switch (m) {
    case Model::kelvin_voigt: return "kelvin-voigt";
    case Model::hertz: return "hertz";
    case Model::hunt_crossley: return "hunt-crossley";
    case Model::jankowski: return "jankowski";
    case Model::jankowski_published: return "jankowski-published";
  }
  return "?";
}

std::string_view summary(Model m) {
  switch (m) {
    case Model::kelvin_voigt: return "linear spring and dashpot while the gap is closed, damping exact for eps";
    case Model::hertz: return "Hertz spring k p^(3/2), elastic (eps = 1 only)";
    case Model::hunt_crossley: return "Hertz spring with Hunt-Crossley damping, chi calibrated to eps";
    case Model::jankowski: return "Hertz spring with Jankowski's damping during approach, zeta calibrated to eps";
    case Model::jankowski_published:
      return "Jankowski's element with his published zeta(eps), which restitutes less than eps";
  }
  return "?";
}

std::optional<Model> parse_model(std::string_view text) {
  if (text.empty()) return Model::kelvin_voigt;
  for (Model m : kModels)
    if (name(m) == text) return m;
  return std::nullopt;
}

std::string_view eps_problem(Model m, double eps) {
  switch (m) {
    case Model::kelvin_voigt: return {};
    case Model::hertz:
      return eps == 1.0 ? std::string_view() : "the hertz element is elastic: it restitutes eps = 1 only";
    case Model::hunt_crossley:
    case Model::jankowski:
    case Model::jankowski_published:
      return eps > 0.0 ? std::string_view()
                       : "its damping grows without bound as eps -> 0: eps must be > 0 (use kelvin-voigt for eps = 0)";
  }
  return {};
}

double kelvin_voigt_zeta(double eps) {
  if (eps <= 0.0) return 1.0;
  const double l = std::log(eps);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

double jankowski_published_zeta(double eps) {
  const double pi = std::numbers::pi;
  return 9.0 * std::sqrt(5.0) * (1.0 - eps * eps) / (2.0 * eps * (eps * (9.0 * pi - 16.0) + 16.0));
}

double lankarani_nikravesh_chi(double eps) { return 0.75 * (1.0 - eps * eps); }
double flores_chi(double eps) { return 8.0 * (1.0 - eps) / (5.0 * eps); }

namespace {

// x'' = -max(0, x^(3/2) (1 + chi x')) from x = 0, x' = 1 until x returns to 0 (or the force
// has ended and x' no longer changes): -x' there. Classical RK4 at a step of 1e-3 of the
// unit time (a contact lasts ~3.2 units): its error, ~h^4 = 1e-12, is below the
// bisection's 1e-10 in eps, and the crossing is placed on a cubic Hermite interpolant.
double restitution_of(double chi) {
  const auto accel = [chi](double x, double v) {
    if (x <= 0.0) return 0.0;
    const double f = std::pow(x, 1.5) * (1.0 + chi * v);
    return f > 0.0 ? -f : 0.0;
  };
  constexpr double h = 1e-3;
  double x = 0.0, v = 1.0;
  for (long i = 0; i < 10'000'000; ++i) {
    const double k1x = v, k1v = accel(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = accel(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = accel(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = accel(x + h * k3x, v + h * k3v);
    const double xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    const double vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    if (i > 0 && xn <= 0.0) {
      // Past the end: the force is tiny there (x^(3/2)), so v barely changes over the
      // crossing; linear interpolation of v at the root of the Hermite cubic is enough.
      double lo = 0.0, hi = 1.0;
      const auto cubic = [&](double s) {
        const double s2 = s * s, s3 = s2 * s;
        return (2 * s3 - 3 * s2 + 1) * x + (s3 - 2 * s2 + s) * h * v + (-2 * s3 + 3 * s2) * xn +
               (s3 - s2) * h * vn;
      };
      for (int b = 0; b < 60; ++b) {
        const double mid = 0.5 * (lo + hi);
        (cubic(mid) > 0.0 ? lo : hi) = mid;
      }
      return -(v + (vn - v) * lo);
    }
    // The force has ended (clamped) and the body flies back at a constant rate.
    if (i > 0 && accel(xn, vn) == 0.0 && vn < 0.0) return -vn;
    x = xn;
    v = vn;
  }
  return std::nan("");
}

// Jankowski's isolated impact in the units of restitution_of: x'' = -x^(3/2) - 2 zeta x^(1/4) x'
// while x' > 0, elastic after, so the rebound returns the energy held at the deepest point:
// e = sqrt(4/5 x_max^(5/2)). x^(1/4) has an unbounded slope at x = 0, where RK4 in t
// converged only as h^1.25 (1e-5 in e at h = 1e-3); in s with t = s^4 the right-hand side
// 4 s^3 (x', x'') is smooth there (x ~ s^4, x^(1/4) ~ s). RK4 at ds = 1e-3 to x' = 0 (about
// 1300 steps), the crossing placed on the cubic Hermite interpolant of x' and x read there:
// e agrees with ds = 3e-4 to 2e-12.
double jankowski_of(double zeta) {
  const auto rhs = [zeta](double s, double x, double v, double& dx, double& dv) {
    const double j = 4.0 * s * s * s, p = std::max(x, 0.0);
    dx = j * v;
    dv = -j * (p * std::sqrt(p) + 2.0 * zeta * std::sqrt(std::sqrt(p)) * v);
  };
  constexpr double ds = 1e-3;
  double s = 0.0, x = 0.0, v = 1.0;
  for (long i = 0; i < 10'000'000; ++i) {
    double k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
    rhs(s, x, v, k1x, k1v);
    rhs(s + 0.5 * ds, x + 0.5 * ds * k1x, v + 0.5 * ds * k1v, k2x, k2v);
    rhs(s + 0.5 * ds, x + 0.5 * ds * k2x, v + 0.5 * ds * k2v, k3x, k3v);
    rhs(s + ds, x + ds * k3x, v + ds * k3v, k4x, k4v);
    const double xn = x + ds / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    const double vn = v + ds / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    if (vn <= 0.0) {
      double enx, env;
      rhs(s + ds, xn, vn, enx, env);
      const auto hermite = [&](double y0, double y1, double d0, double d1, double u) {
        const double u2 = u * u, u3 = u2 * u;
        return (2 * u3 - 3 * u2 + 1) * y0 + (u3 - 2 * u2 + u) * ds * d0 + (-2 * u3 + 3 * u2) * y1 + (u3 - u2) * ds * d1;
      };
      double lo = 0.0, hi = 1.0;
      for (int b = 0; b < 60; ++b) {
        const double mid = 0.5 * (lo + hi);
        (hermite(v, vn, k1v, env, mid) > 0.0 ? lo : hi) = mid;
      }
      const double deepest = hermite(x, xn, k1x, enx, lo);
      return std::sqrt(0.8 * deepest * deepest * std::sqrt(deepest));
    }
    s += ds;
    x = xn;
    v = vn;
  }
  return std::nan("");
}

// The damping parameter whose restitution (falling as it grows, 1 at 0) is eps, bisected to
// 1e-11 of itself, once per eps: each cache is shared by every thread's runs.
double calibrated(double eps, double (*restitution)(double), std::map<double, double>& cache, std::mutex& mutex) {
  if (eps >= 1.0) return 0.0;
  {
    const std::lock_guard lock(mutex);
    if (auto it = cache.find(eps); it != cache.end()) return it->second;
  }
  double lo = 0.0, hi = 1.0;
  while (restitution(hi) > eps && hi < 1e6) lo = hi, hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-11 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (restitution(mid) > eps ? lo : hi) = mid;
  }
  const double value = 0.5 * (lo + hi);
  const std::lock_guard lock(mutex);
  cache.emplace(eps, value);
  return value;
}

}  // namespace

double hunt_crossley_restitution(double chi) { return restitution_of(chi); }
double jankowski_restitution(double zeta) { return jankowski_of(zeta); }

double hunt_crossley_chi(double eps) {
  static std::mutex mutex;
  static std::map<double, double> cache;  // eps -> chi
  return calibrated(eps, &restitution_of, cache, mutex);
}

double jankowski_zeta(double eps) {
  static std::mutex mutex;
  static std::map<double, double> cache;  // eps -> zeta_J
  return calibrated(eps, &jankowski_of, cache, mutex);
}

Law make_law(Model model, double k, double eps, double m_left, double m_right) {
  Law law;
  law.model = model;
  law.k = k;
  law.m_eff = m_left > 0.0 ? m_left * m_right / (m_left + m_right) : m_right;
  switch (model) {
    case Model::kelvin_voigt:
      law.zeta = kelvin_voigt_zeta(eps);
      law.c = 2.0 * law.zeta * std::sqrt(k * law.m_eff);
      break;
    case Model::hertz: break;
    case Model::hunt_crossley: law.chi = hunt_crossley_chi(eps); break;
    case Model::jankowski: law.zeta = jankowski_zeta(eps); break;
    case Model::jankowski_published: law.zeta = jankowski_published_zeta(eps); break;
  }
  return law;
}

double Law::force(double p, double q, double v_minus) const {
  if (!(p > 0.0)) return 0.0;
  switch (model) {
    case Model::kelvin_voigt: return k * p + c * q;
    case Model::hertz: return k * p * std::sqrt(p);
    case Model::hunt_crossley: return std::max(0.0, k * p * std::sqrt(p) * (1.0 + chi * q / v_minus));
    case Model::jankowski:
    case Model::jankowski_published:
      return k * p * std::sqrt(p) + (q > 0.0 ? 2.0 * zeta * std::sqrt(k * std::sqrt(p) * m_eff) * q : 0.0);
  }
  return 0.0;
}

void Law::slopes(double p, double q, double v_minus, double& dp, double& dq) const {
  dp = dq = 0.0;
  if (!(p > 0.0)) return;
  const double sp = std::sqrt(p);
  switch (model) {
    case Model::kelvin_voigt:
      dp = k;
      dq = c;
      return;
    case Model::hertz: dp = 1.5 * k * sp; return;
    case Model::hunt_crossley: {
      const double damp = 1.0 + chi * q / v_minus;
      if (damp <= 0.0) return;
      dp = 1.5 * k * sp * damp;
      dq = k * p * sp * chi / v_minus;
      return;
    }
    case Model::jankowski:
    case Model::jankowski_published: {
      dp = 1.5 * k * sp;
      if (q > 0.0) {
        const double cq = 2.0 * zeta * std::sqrt(k * m_eff);
        dp += cq * 0.25 * std::pow(p, -0.75) * q;
        dq = cq * std::pow(p, 0.25);
      }
      return;
    }
  }
}

}  // namespace pb::compliant
