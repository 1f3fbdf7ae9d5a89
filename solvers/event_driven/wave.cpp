#include "solvers/event_driven/wave.hpp"

#include <cassert>
#include <complex>

namespace pb::event_driven {

namespace {

// sin and cos of w t0. Every wave of a frame shares w and t0, and a frame prepares several
// per body, so the last pair is kept (per thread); the values are the same either way.
void sin_cos(double w, double t0, double& s, double& c) {
  thread_local double last_w = 0.0, last_t0 = 0.0, last_s = 0.0, last_c = 1.0;
  if (w == 0.0) {  // after the pulse most waves have no pulse term
    s = 0.0;
    c = 1.0;
    return;
  }
  if (w != last_w || t0 != last_t0) {
    last_w = w;
    last_t0 = t0;
    last_s = std::sin(w * t0);
    last_c = std::cos(w * t0);
  }
  s = last_s;
  c = last_c;
}

using Complex = std::complex<double>;

bool resonant(const Mode& md) { return md.rr != 0.0 || md.ri != 0.0; }

// E(s) = (exp(d s) - 1) / d, d = sigma + i delta (= i w - z), without the cancellation of
// exp(d s) - 1 for small |d s|: exp(x) - 1 = expm1(xr) cos(xi) - 2 sin^2(xi / 2) + i exp(xr) sin(xi).
Complex grow(double sigma, double delta, double s) {
  const Complex d(sigma, delta), x = d * s;
  if (std::abs(x) < 1e-4) return s * (1.0 + x * (0.5 + x * (1.0 / 6.0 + x / 24.0)));  // x^4/120 < 1e-18
  const double h = std::sin(0.5 * x.imag());
  return Complex(std::expm1(x.real()) * std::cos(x.imag()) - 2.0 * h * h, std::exp(x.real()) * std::sin(x.imag())) /
         d;
}

}  // namespace

void Wave::prepare() {
  for (int m = 0; m < n_modes; ++m) {
    Mode& md = mode[static_cast<std::size_t>(m)];
    // (a - i b) * lambda^d with lambda = -sigma + i omega.
    double re = md.a, im = -md.b;
    md.re[0] = re;
    md.im[0] = im;
    for (std::size_t d = 1; d <= kMaxDerivative; ++d) {
      const double nre = re * -md.sigma - im * md.omega;
      const double nim = re * md.omega + im * -md.sigma;
      re = nre;
      im = nim;
      md.re[d] = re;
      md.im[d] = im;
    }
    const double rate = std::hypot(md.sigma, md.omega);
    md.envelope[0] = std::hypot(md.a, md.b);
    for (std::size_t d = 1; d <= kMaxDerivative; ++d) md.envelope[d] = md.envelope[d - 1] * rate;
  }
  sin_cos(w, t0, s0, c0);
  pulse_envelope[0] = std::hypot(ps, pc);
  for (std::size_t d = 1; d <= kMaxDerivative; ++d) pulse_envelope[d] = pulse_envelope[d - 1] * w;
}

void Wave::eval(double t, double* out, int nd) const {
  const double tau = t - t0;
  // Searches start where the wave does (tau = 0): there the functions below are skipped
  // for their exact values (sin 0 = 0, cos 0 = 1, expm1(-0) = -0).
  const bool start = tau == 0.0;
  for (int d = 0; d < nd; ++d) out[d] = 0.0;
  out[0] = f0;
  if (ps != 0.0 || pc != 0.0) {
    // sin(w t) - sin(w t0) and cos(w t) - cos(w t0) from the half angle of w (t - t0),
    // free of cancellation near t0.
    double sh = 0.0, ch = 1.0;
    if (!start) {
      sh = std::sin(0.5 * w * tau);
      ch = std::cos(0.5 * w * tau);
    }
    const double dc = -2.0 * sh * sh, ds = 2.0 * sh * ch;  // cos(w tau) - 1, sin(w tau)
    out[0] += ps * (s0 * dc + c0 * ds) + pc * (c0 * dc - s0 * ds);
    if (nd > 1) {
      const double s = s0 + (s0 * dc + c0 * ds);  // sin(w t)
      const double c = c0 + (c0 * dc - s0 * ds);  // cos(w t)
      // d-th derivative: w^d (ps sin(wt + d pi/2) + pc cos(wt + d pi/2)).
      double wd = 1.0;
      for (int d = 1; d < nd; ++d) {
        wd *= w;
        double v = 0.0;
        switch (d % 4) {
          case 0: v = ps * s + pc * c; break;
          case 1: v = ps * c - pc * s; break;
          case 2: v = -ps * s - pc * c; break;
          case 3: v = -ps * c + pc * s; break;
        }
        out[d] += wd * v;
      }
    }
  }
  for (int m = 0; m < n_modes; ++m) {
    const Mode& md = mode[static_cast<std::size_t>(m)];
    double em1 = -0.0, sh = 0.0, ch = 1.0;
    if (!start) {
      em1 = std::expm1(-md.sigma * tau);
      sh = std::sin(0.5 * md.omega * tau);
      ch = std::cos(0.5 * md.omega * tau);
    }
    const double e = em1 + 1.0;
    const double cs = 1.0 - 2.0 * sh * sh, sn = 2.0 * sh * ch;
    // e cs - 1 = expm1 cs - 2 sh^2, without cancellation near tau = 0.
    out[0] += md.a * (em1 * cs - 2.0 * sh * sh) + md.b * e * sn;
    for (int d = 1; d < nd; ++d) {
      const auto k = static_cast<std::size_t>(d);
      out[d] += e * (md.re[k] * cs - md.im[k] * sn);
    }
    if (resonant(md)) {
      // G^(d)(s) = exp(z s) [(i w)^d E(s) + S_d], S_d = sum_{j<d} (i w)^j z^(d-1-j): the
      // difference quotient of (i w)^d exp(i w s) and z^d exp(z s), free of 1 / |i w - z|.
      const Complex ez(e * cs, e * sn), iw(0.0, w), z(-md.sigma, md.omega);
      const Complex grown = start ? Complex(0.0) : grow(md.sigma, w - md.omega, tau);
      Complex a(md.rr, md.ri), sum(0.0);  // r (i w)^d, r S_d
      for (int d = 0; d < nd; ++d) {
        out[d] += (ez * (a * grown + sum)).real();
        sum = sum * z + a;
        a *= iw;
      }
    }
  }
}

double Wave::bound(double t, int d) const {
  const auto k = static_cast<std::size_t>(d);
  double b = pulse_envelope[k];
  const double tau = std::max(t - t0, 0.0);
  for (int m = 0; m < n_modes; ++m) {
    const Mode& md = mode[static_cast<std::size_t>(m)];
    const double decay = tau == 0.0 ? 1.0 : std::exp(-md.sigma * tau);
    b += md.envelope[k] * decay;
    if (resonant(md)) {
      // |exp(z s) E(s)| = |exp(i w s) - exp(z s)| / |d| <= 2 / |d|, and <= s (sigma >= 0).
      const double d_abs = std::hypot(md.sigma, w - md.omega), z_abs = std::hypot(md.sigma, md.omega);
      const double reach = std::min(horizon - t0, d_abs > 0.0 ? 2.0 / d_abs : horizon - t0);
      double wd = 1.0, sum = 0.0;  // w^k, sum_{j<k} w^j |z|^(k-1-j)
      for (int j = 0; j < d; ++j) {
        sum = sum * z_abs + wd;
        wd *= w;
      }
      b += std::hypot(md.rr, md.ri) * (wd * reach + sum * decay);
    }
  }
  return b;
}

double Wave::mean() const {
  double m = f0 - ps * s0 - pc * c0;
  for (int k = 0; k < n_modes; ++k) m -= mode[static_cast<std::size_t>(k)].a;
  return m;
}

void add_scaled(Wave& acc, const Wave& x, double s) {
  assert(acc.t0 == x.t0);
  acc.f0 += s * x.f0;
  if (x.w != 0.0) {
    assert(acc.w == 0.0 || acc.w == x.w);
    acc.w = x.w;
    acc.ps += s * x.ps;
    acc.pc += s * x.pc;
  }
  acc.horizon = std::min(acc.horizon, x.horizon);
  for (int m = 0; m < x.n_modes; ++m) {
    const Mode& xm = x.mode[static_cast<std::size_t>(m)];
    int k = 0;
    while (k < acc.n_modes && !(acc.mode[static_cast<std::size_t>(k)].sigma == xm.sigma &&
                                acc.mode[static_cast<std::size_t>(k)].omega == xm.omega))
      ++k;
    assert(k < kMaxModes);
    Mode& am = acc.mode[static_cast<std::size_t>(k)];
    if (k == acc.n_modes) {
      am = Mode{};
      am.sigma = xm.sigma;
      am.omega = xm.omega;
      ++acc.n_modes;
    }
    am.a += s * xm.a;
    am.b += s * xm.b;
    am.rr += s * xm.rr;
    am.ri += s * xm.ri;
  }
}

Wave derivative(const Wave& x) {
  Wave d;
  d.t0 = x.t0;
  double v[2];
  x.eval(x.t0, v, 2);
  d.f0 = v[1];
  d.w = x.w;
  d.ps = -x.w * x.pc;
  d.pc = x.w * x.ps;
  d.horizon = x.horizon;
  d.n_modes = x.n_modes;
  for (int m = 0; m < x.n_modes; ++m) {
    const Mode& xm = x.mode[static_cast<std::size_t>(m)];
    Mode& dm = d.mode[static_cast<std::size_t>(m)];
    dm.sigma = xm.sigma;
    dm.omega = xm.omega;
    // (r G)' = (i w r) G + r exp(z s): the damped term gains r, the resonant one i w r.
    dm.a = xm.re[1] + xm.rr;
    dm.b = -(xm.im[1] + xm.ri);
    dm.rr = -x.w * xm.ri;
    dm.ri = x.w * xm.rr;
  }
  d.prepare();
  return d;
}

Wave oscillator(double t0, double x0, double v0, double m, double c, double k, double f_const, double fs,
                double fc, double w, double horizon) {
  Wave x;
  x.t0 = t0;
  x.f0 = x0;
  x.horizon = horizon;
  const double wn2 = k / m;
  const double two_zeta_wn = c / m;
  const double sigma = 0.5 * two_zeta_wn;
  const double omega = std::sqrt(wn2 - sigma * sigma);
  Mode& md = x.mode[0];
  md.sigma = sigma;
  md.omega = omega;
  x.n_modes = 1;
  const bool forced = fs != 0.0 || fc != 0.0;
  if (forced && std::hypot(sigma, w - omega) < kNearResonance * w) {
    // The load is Re(F exp(i w t)), F = fc - i fs. From rest at t0 it moves the oscillator
    // by Re(F' / m) times the divided difference of exp(p s) over the poles p = i w, z,
    // conj(z) (F' = F exp(i w t0)), which is (G(s) - exp(-sigma s) sin(omega s) / omega) /
    // (i w - conj z): the near-resonant term with r = F' / (m (i w - conj z)), and a sine.
    // The free motion from (x0 - F0 / K, v0) adds the usual damped term.
    x.w = w;
    const Complex r = Complex(fc, -fs) * std::polar(1.0, w * t0) / (m * Complex(sigma, w + omega));
    md.a = x0 - f_const / k;
    md.b = (v0 + sigma * md.a - r.real()) / omega;
    md.rr = r.real();
    md.ri = r.imag();
    x.prepare();
    return x;
  }
  // Particular solution: f_const / k + P sin(w t) + Q cos(w t).
  double p = 0.0, q = 0.0;
  if (forced) {
    const double a = wn2 - w * w, b = two_zeta_wn * w;
    const double det = a * a + b * b;
    p = (a * fs / m + b * fc / m) / det;
    q = (a * fc / m - b * fs / m) / det;
    x.w = w;
    x.ps = p;
    x.pc = q;
  }
  double sn, cs;
  sin_cos(x.w, t0, sn, cs);
  const double xp = f_const / k + p * sn + q * cs;
  const double vp = w * (p * cs - q * sn);
  md.a = x0 - xp;
  md.b = (v0 - vp + sigma * md.a) / omega;
  x.prepare();
  return x;
}

Wave constant(double t0, double f0) {
  Wave x;
  x.t0 = t0;
  x.f0 = f0;
  return x;
}

}  // namespace pb::event_driven
