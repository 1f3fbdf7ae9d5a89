#include "solvers/event_driven/wave.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <complex>
#include <cstdint>
#include <numbers>

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

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

using Complex = std::complex<double>;

bool resonant(const Mode& md, int j) {
  const auto k = static_cast<std::size_t>(j);
  return md.rr[k] != 0.0 || md.ri[k] != 0.0;
}

// E(s) = (exp(d s) - 1) / d, d = sigma + i delta (= i w - z), without the cancellation of
// exp(d s) - 1 for small |d s|: exp(x) - 1 = expm1(xr) cos(xi) - 2 sin^2(xi / 2) + i exp(xr) sin(xi).
Complex grow(double sigma, double delta, double s) {
  const Complex d(sigma, delta), x = d * s;
  if (std::abs(x) < 1e-4) return s * (1.0 + x * (0.5 + x * (1.0 / 6.0 + x / 24.0)));  // x^4/120 < 1e-18
  const double h = std::sin(0.5 * x.imag());
  return Complex(std::expm1(x.real()) * std::cos(x.imag()) - 2.0 * h * h, std::exp(x.real()) * std::sin(x.imag())) /
         d;
}

// The coefficients of h0 and h1 in each derivative of a general mode (Mode::general):
// (a, b, c2, c3) -> (-sigma a + b, -w2 a - sigma b + c2, c3, 0).
void prepare_general(Mode& md) {
  double a = md.a, b = md.b, c2 = md.c2, c3 = md.c3;
  for (std::size_t d = 0; d <= kMaxDerivative; ++d) {
    md.re[d] = a;
    md.im[d] = b;
    const double na = -md.sigma * a + b, nb = -md.w2 * a - md.sigma * b + c2;
    a = na;
    b = nb;
    c2 = c3;
    c3 = 0.0;
  }
  md.envelope.fill(0.0);
}

// 1 / k! for the series below.
constexpr std::array<double, 28> kInverseFactorial = [] {
  std::array<double, 28> f{};
  double x = 1.0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    f[k] = 1.0 / x;
    x *= static_cast<double>(k + 1);
  }
  return f;
}();

// The basis of a general mode at s > 0 (Mode::general): h0 - 1 and h0, h1, h2, h3, each to
// the round-off of its own size (DERIVATION.md §10).
struct GeneralBasis {
  double h0m1, h0, h1, h2, h3;
};

template <class Trig>
GeneralBasis general_basis(const Mode& md, double s, Trig& trig) {
  GeneralBasis g;
  const double sigma = md.sigma, k_m = md.k_m;
  const double reach = (md.w2 < 0.0 ? md.fast : std::sqrt(k_m)) * s;  // the largest |root| s
  if (reach <= 1.0) {
    // Every root within 1 / s of zero: the divided differences of exp(x s) over the roots
    // (and 0, 0) as Taylor series, sum_k p_k / (k + n)! with p_k = h_k(lambda_1 s,
    // lambda_2 s), the complete homogeneous polynomials, which follow p_k = e1 p_k-1 -
    // e2 p_k-2 from their sum e1 = -2 sigma s and product e2 = k_m s^2, real for either
    // sign of w2. |p_k| <= (k + 1) reach^k, so 24 terms are below 2e-23.
    const double e1 = -2.0 * sigma * s, e2 = k_m * s * s;
    double p_before = 0.0, p = 1.0;
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    for (std::size_t k = 0; k < 24; ++k) {
      if (k > 0) s0 += p * kInverseFactorial[k];
      s1 += p * kInverseFactorial[k + 1];
      s2 += p * kInverseFactorial[k + 2];
      s3 += p * kInverseFactorial[k + 3];
      const double next = e1 * p - e2 * p_before;
      p_before = p;
      p = next;
    }
    g.h1 = s * s1;
    g.h0m1 = s0 + sigma * g.h1;  // h0 = h1' + sigma h1, h1' = sum p_k / k!
    g.h0 = 1.0 + g.h0m1;
    g.h2 = s * s * s2;
    g.h3 = s * s * s * s3;
    return g;
  }
  if (md.w2 >= 0.0) {
    // Complex (or double) roots, |root| s > 1: the damped sinusoid, h2 and h3 from the
    // equation of motion, k_m h2 = 1 - h0 - sigma h1 and k_m h3 = s - h1 - 2 sigma h2, which
    // lose nothing against the size of h2 (>= 1 / (2 k_m) here) or h3.
    const double omega = md.omega, x = omega * s;
    double sh, ch;
    trig.sin_cos(0.5 * x, sh, ch);
    const double em1 = trig.expm1(-sigma * s), e = em1 + 1.0;
    const double cs = 1.0 - 2.0 * sh * sh;
    const double sinc = x < 1e-3 ? s * (1.0 - x * x / 6.0 + x * x * x * x / 120.0) : 2.0 * sh * ch / omega;
    g.h0m1 = em1 * cs - 2.0 * sh * sh;
    g.h0 = e * cs;
    g.h1 = e * sinc;
    g.h2 = (-g.h0m1 - sigma * g.h1) / k_m;
    g.h3 = (s - g.h1 - 2.0 * sigma * g.h2) / k_m;
    return g;
  }
  // Real roots lambda_2 = -fast <= lambda_1 = -slow <= 0, fast s > 1: Newton's divided
  // differences in the order lambda_2, lambda_1, 0, 0, each difference over fast >= 1 / s,
  // of terms that are not close (their ratio stays below about 3 for every lambda_1).
  const double l1 = -md.slow, l2 = -md.fast, gap = 2.0 * md.omega;  // lambda_1 - lambda_2
  const double e1 = trig.expm1(l1 * s), e2 = trig.expm1(l2 * s);
  g.h0m1 = 0.5 * (e1 + e2);
  g.h0 = 1.0 + g.h0m1;
  const double x = gap * s;
  if (x > 1.0) {
    g.h1 = (e1 - e2) / gap;
  } else {
    const double phi1 = x == 0.0 ? 1.0 : trig.expm1(x) / x;  // (exp(x) - 1) / x
    g.h1 = (e2 + 1.0) * s * phi1;
  }
  const double z = l1 * s;  // in (-1 / ..., 0]
  const double d1 = l1 == 0.0 ? s : e1 / l1;  // divided difference over lambda_1, 0
  double phi2;                                  // (exp(z) - 1 - z) / z^2
  if (std::abs(z) < 0.5) {
    phi2 = 0.0;
    double zk = 1.0;
    for (std::size_t k = 0; k < 18; ++k, zk *= z) phi2 += zk * kInverseFactorial[k + 2];
  } else {
    phi2 = (e1 - z) / (z * z);
  }
  g.h2 = (d1 - g.h1) / md.fast;
  g.h3 = (s * s * phi2 - g.h2) / md.fast;
  return g;
}

}  // namespace

void Wave::prepare() {
  for (int m = 0; m < n_modes; ++m) {
    Mode& md = mode[static_cast<std::size_t>(m)];
    if (md.general) {
      prepare_general(md);
      continue;
    }
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
    if (!(md.rate >= 0.0)) md.rate = std::hypot(md.sigma, md.omega);
    const double rate = md.rate;
    md.envelope[0] = std::hypot(md.a, md.b);
    for (std::size_t d = 1; d <= kMaxDerivative; ++d) md.envelope[d] = md.envelope[d - 1] * rate;
  }
  any_resonant = false;
  for (int m = 0; m < n_modes; ++m)
    for (int j = 0; j < n_sines; ++j) any_resonant = any_resonant || resonant(mode[static_cast<std::size_t>(m)], j);
  pulse_envelope.fill(0.0);
  for (int j = 0; j < n_sines; ++j) {
    Sine& p = sine[static_cast<std::size_t>(j)];
    sin_cos(p.w, t0, p.s0, p.c0);
    double e = std::hypot(p.ps, p.pc);
    pulse_envelope[0] += e;
    for (std::size_t d = 1; d <= kMaxDerivative; ++d) {
      e *= p.w;
      pulse_envelope[d] += e;
    }
  }
}

namespace {

// libm's functions as they are (a search's evaluations).
struct PlainTrig {
  void sin_cos(double x, double& s, double& c) const {
    s = std::sin(x);
    c = std::cos(x);
  }
  double expm1(double x) const { return std::expm1(x); }
};

}  // namespace

void TrigCache::sin_cos(double x, double& s, double& c) {
  for (int k = 0; k < n_sc_; ++k) {
    const SinCos& e = sc_[static_cast<std::size_t>(k)];
    if (same_bits(e.x, x)) {
      s = e.s;
      c = e.c;
      return;
    }
  }
  s = std::sin(x);
  c = std::cos(x);
  sc_[static_cast<std::size_t>(next_sc_)] = {x, s, c};
  next_sc_ = (next_sc_ + 1) % kSize;
  n_sc_ = std::min(n_sc_ + 1, kSize);
}

double TrigCache::expm1(double x) {
  for (int k = 0; k < n_em_; ++k) {
    const Expm1& e = em_[static_cast<std::size_t>(k)];
    if (same_bits(e.x, x)) return e.e;
  }
  const double v = std::expm1(x);
  em_[static_cast<std::size_t>(next_em_)] = {x, v};
  next_em_ = (next_em_ + 1) % kSize;
  n_em_ = std::min(n_em_ + 1, kSize);
  return v;
}

namespace {

// nd is a template argument so that the loops over derivatives unroll: the searches ask for
// 2 or 3 values at a time, and eval is the reference's largest cost. The same operations in
// the same order whatever nd is, so the same values.
// Each term eval adds to f0 passes through `term` (WaveAt keeps them; otherwise the term as
// it is), which changes no value and no order of the additions.
struct AsItIs {
  double operator()(double x) const { return x; }
};
struct KeepTerms {
  WaveAt& at;
  double operator()(double x) {
    at.term[static_cast<std::size_t>(at.n++)] = x;
    return x;
  }
};

template <int nd, class Trig, class Term = AsItIs>
void eval_wave(const Wave& wave, double t, double* out, Trig& trig, Term term = {}) {
  const double t0 = wave.t0, f0 = wave.f0, lin = wave.lin;
  const int n_sines = wave.n_sines, n_modes = wave.n_modes;
  const auto& sine = wave.sine;
  const auto& mode = wave.mode;
  const double tau = t - t0;
  // Searches start where the wave does (tau = 0): there the functions below are skipped
  // for their exact values (sin 0 = 0, cos 0 = 1, expm1(-0) = -0).
  const bool start = tau == 0.0;
  for (int d = 0; d < nd; ++d) out[d] = 0.0;
  out[0] = f0;
  if (lin != 0.0) {
    out[0] += term(lin * tau);
    if (nd > 1) out[1] += lin;
  }
  for (int j = 0; j < n_sines; ++j) {
    const Sine& p = sine[static_cast<std::size_t>(j)];
    const double w = p.w, ps = p.ps, pc = p.pc, s0 = p.s0, c0 = p.c0;
    if (ps == 0.0 && pc == 0.0) continue;
    // sin(w t) - sin(w t0) and cos(w t) - cos(w t0) from the half angle of w (t - t0),
    // free of cancellation near t0.
    double sh = 0.0, ch = 1.0;
    if (!start) {
      trig.sin_cos(0.5 * w * tau, sh, ch);
    }
    const double dc = -2.0 * sh * sh, ds = 2.0 * sh * ch;  // cos(w tau) - 1, sin(w tau)
    out[0] += term(ps * (s0 * dc + c0 * ds) + pc * (c0 * dc - s0 * ds));
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
    if (md.general) [[unlikely]] {
      if (start) {  // h0 = 1, h1 = h2 = h3 = 0
        for (int d = 1; d < nd; ++d) out[d] += md.re[static_cast<std::size_t>(d)];
        continue;
      }
      const GeneralBasis g = general_basis(md, tau, trig);
      out[0] += term(md.a * g.h0m1 + md.b * g.h1 + md.c2 * g.h2 + md.c3 * g.h3);
      if (nd > 1) out[1] += md.re[1] * g.h0 + md.im[1] * g.h1 + md.c3 * g.h2;
      for (int d = 2; d < nd; ++d) {
        const auto k = static_cast<std::size_t>(d);
        out[d] += md.re[k] * g.h0 + md.im[k] * g.h1;
      }
      continue;
    }
    double em1 = -0.0, sh = 0.0, ch = 1.0;
    if (!start) {
      em1 = trig.expm1(-md.sigma * tau);
      trig.sin_cos(0.5 * md.omega * tau, sh, ch);
    }
    const double e = em1 + 1.0;
    const double cs = 1.0 - 2.0 * sh * sh, sn = 2.0 * sh * ch;
    // e cs - 1 = expm1 cs - 2 sh^2, without cancellation near tau = 0.
    out[0] += term(md.a * (em1 * cs - 2.0 * sh * sh) + md.b * e * sn);
    for (int d = 1; d < nd; ++d) {
      const auto k = static_cast<std::size_t>(d);
      out[d] += e * (md.re[k] * cs - md.im[k] * sn);
    }
    for (int j = 0; j < n_sines; ++j) {
      if (!resonant(md, j)) continue;
      const double w = sine[static_cast<std::size_t>(j)].w;
      // G^(d)(s) = exp(z s) [(i w)^d E(s) + S_d], S_d = sum_{j<d} (i w)^j z^(d-1-j): the
      // difference quotient of (i w)^d exp(i w s) and z^d exp(z s), free of 1 / |i w - z|.
      const Complex ez(e * cs, e * sn), iw(0.0, w), z(-md.sigma, md.omega);
      const Complex grown = start ? Complex(0.0) : grow(md.sigma, w - md.omega, tau);
      Complex a(md.rr[static_cast<std::size_t>(j)], md.ri[static_cast<std::size_t>(j)]), sum(0.0);  // r (i w)^d, r S_d
      for (int d = 0; d < nd; ++d) {
        const double part = (ez * (a * grown + sum)).real();
        out[d] += d == 0 ? term(part) : part;
        sum = sum * z + a;
        a *= iw;
      }
    }
  }
}

template <class Trig>
void eval_any(const Wave& wave, double t, double* out, int nd, Trig& trig) {
  switch (nd) {
    case 1: return eval_wave<1>(wave, t, out, trig);
    case 2: return eval_wave<2>(wave, t, out, trig);
    case 3: return eval_wave<3>(wave, t, out, trig);
    case 4: return eval_wave<4>(wave, t, out, trig);
    case 5: return eval_wave<5>(wave, t, out, trig);
    default: return eval_wave<kMaxDerivative + 1>(wave, t, out, trig);
  }
}

}  // namespace

void Wave::eval(double t, double* out, int nd) const {
  assert(nd >= 1 && nd <= kMaxDerivative + 1);
  PlainTrig trig;
  eval_any(*this, t, out, nd, trig);
}

void Wave::eval(double t, double* out, int nd, TrigCache& trig) const {
  assert(nd >= 1 && nd <= kMaxDerivative + 1);
  eval_any(*this, t, out, nd, trig);
}

void Wave::eval_at(double t, WaveAt& at, TrigCache& trig) const {
  double out[2];
  at.n = 0;
  eval_wave<2>(*this, t, out, trig, KeepTerms{at});
  at.rate = out[1];
}

double WaveAt::value(double f0) const {
  double u = f0;
  for (int k = 0; k < n; ++k) u += term[static_cast<std::size_t>(k)];
  return u;
}

void Wave::decays(double t, double* decay) const {
  const double tau = std::max(t - t0, 0.0);
  for (int m = 0; m < n_modes; ++m) {
    const Mode& md = mode[static_cast<std::size_t>(m)];
    decay[m] = tau == 0.0 ? 1.0 : std::exp(-(md.general ? md.slow : md.sigma) * tau);
  }
}

double Wave::bound(double t, int d) const {
  double decay[kMaxModes];
  decays(t, decay);
  return bound_at(t, decay, d);
}

namespace {

// An upper bound of |G^(d)(s)| over tau <= s <= span (s from the mode's start) for a general
// mode, from bounds of its basis there (DERIVATION.md §10), decay = exp(-slow tau):
//   |h0| <= decay;  |h1| <= s exp(-slow s), and <= decay min(span, 1 / omega) (w2 > 0), or
//   decay min(span, 1 / (2 omega)) (w2 < 0: exp(l1 s) (1 - exp(-2 omega s)) / (2 omega));
//   h2, h3: |divided differences| <= span^n / n!, and by the equation of motion (w2 >= 0)
//   or by the monotonicity of divided differences of exp in their nodes (w2 < 0).
// An unbounded growth (no stiffness, no damping, an infinite span) gives infinity, which a
// search refuses (NonFinite): the frame gives such a wave a finite horizon.
double general_bound(const Mode& md, double decay, double tau, double span, int d) {
  const double inf = std::numeric_limits<double>::infinity();
  double cap = span;
  if (md.w2 > 0.0) cap = std::min(span, 1.0 / md.omega);
  if (md.w2 < 0.0) cap = std::min(span, 0.5 / md.omega);
  double h1 = std::isinf(cap) ? cap : decay * cap;
  if (md.slow > 0.0) h1 = std::min(h1, tau >= 1.0 / md.slow ? tau * decay : 1.0 / (std::numbers::e * md.slow));
  const auto k = static_cast<std::size_t>(d);
  double b = std::abs(md.re[k]) * decay + (md.im[k] != 0.0 ? std::abs(md.im[k]) * h1 : 0.0);
  if (d > 1 || (md.c2 == 0.0 && md.c3 == 0.0)) return b;
  double h2, h3;
  if (md.w2 >= 0.0) {
    h2 = md.k_m > 0.0 ? (1.0 + decay + md.sigma * h1) / md.k_m : inf;
    h3 = md.k_m > 0.0 ? (span + h1 + 2.0 * md.sigma * h2) / md.k_m : inf;
  } else {
    h2 = std::min(span / md.fast, md.slow > 0.0 ? 1.0 / md.k_m : inf);
    h3 = std::min(0.5 * span * span / md.fast, md.slow > 0.0 ? span / md.k_m : inf);
  }
  h2 = std::min(h2, 0.5 * span * span);
  h3 = std::min(h3, span * span * span / 6.0);
  if (d == 0) return b + (md.c2 != 0.0 ? std::abs(md.c2) * h2 : 0.0) + (md.c3 != 0.0 ? std::abs(md.c3) * h3 : 0.0);
  return b + (md.c3 != 0.0 ? std::abs(md.c3) * h2 : 0.0);
}

}  // namespace

double Wave::bound_at(double t, const double* decay_of, int d) const {
  const auto k = static_cast<std::size_t>(d);
  double b = pulse_envelope[k];
  for (int m = 0; m < n_modes; ++m) {
    const Mode& md = mode[static_cast<std::size_t>(m)];
    const double decay = decay_of[m];
    if (md.general) [[unlikely]] {
      b += general_bound(md, decay, std::max(t - t0, 0.0), horizon - t0, d);
      continue;
    }
    b += md.envelope[k] * decay;
    if (!any_resonant) continue;  // the same sum, without looking at every r_mj
    for (int q = 0; q < n_sines; ++q) {
      if (!resonant(md, q)) continue;
      const double w = sine[static_cast<std::size_t>(q)].w;
      // |exp(z s) E(s)| = |exp(i w s) - exp(z s)| / |d| <= 2 / |d|, and <= s (sigma >= 0).
      const double d_abs = std::hypot(md.sigma, w - md.omega), z_abs = std::hypot(md.sigma, md.omega);
      const double reach = std::min(horizon - t0, d_abs > 0.0 ? 2.0 / d_abs : horizon - t0);
      double wd = 1.0, sum = 0.0;  // w^k, sum_{j<k} w^j |z|^(k-1-j)
      for (int j = 0; j < d; ++j) {
        sum = sum * z_abs + wd;
        wd *= w;
      }
      b += std::hypot(md.rr[static_cast<std::size_t>(q)], md.ri[static_cast<std::size_t>(q)]) * (wd * reach + sum * decay);
    }
  }
  if (lin != 0.0) {
    // lin (s - t0) for t0 <= s <= horizon (finite: a linear load ends at its next sample):
    // its value halfway, mean(), plus at most half its rise; slope lin; nothing higher.
    if (d == 0) b += 0.5 * std::abs(lin) * (horizon - t0);
    if (d == 1) b += std::abs(lin);
  }
  return b;
}

double Wave::mean() const {
  double m = f0;
  for (int j = 0; j < n_sines; ++j) {
    const Sine& p = sine[static_cast<std::size_t>(j)];
    m = m - p.ps * p.s0 - p.pc * p.c0;
  }
  for (int k = 0; k < n_modes; ++k) m -= mode[static_cast<std::size_t>(k)].a;
  if (lin != 0.0) m += 0.5 * lin * (horizon - t0);
  return m;
}

namespace {

// Gives a fresh mode (no coefficients) the oscillator of `from`: its rates and, for a
// general mode, its stiffness and roots. A sum or a derivative of a mode keeps these.
void take_oscillator(Mode& to, const Mode& from) {
  to.sigma = from.sigma;
  to.omega = from.omega;
  to.rate = from.rate;
  if (!from.general) return;
  to.general = true;
  to.k_m = from.k_m;
  to.w2 = from.w2;
  to.slow = from.slow;
  to.fast = from.fast;
}

}  // namespace

void add_scaled(Wave& acc, const Wave& x, double s) {
  assert(acc.t0 == x.t0);
  acc.f0 += s * x.f0;
  if (x.lin != 0.0) acc.lin += s * x.lin;
  // Sinusoid j of x is sinusoid at[j] of acc (the same frequency; appended if acc has none).
  std::array<std::size_t, kMaxSines> at{};
  for (int j = 0; j < x.n_sines; ++j) {
    const Sine& xs = x.sine[static_cast<std::size_t>(j)];
    int k = 0;
    while (k < acc.n_sines && acc.sine[static_cast<std::size_t>(k)].w != xs.w) ++k;
    assert(k < kMaxSines);
    Sine& as = acc.sine[static_cast<std::size_t>(k)];
    if (k == acc.n_sines) {
      as = Sine{};
      as.w = xs.w;
      ++acc.n_sines;
    }
    as.ps += s * xs.ps;
    as.pc += s * xs.pc;
    at[static_cast<std::size_t>(j)] = static_cast<std::size_t>(k);
  }
  acc.horizon = std::min(acc.horizon, x.horizon);
  for (int m = 0; m < x.n_modes; ++m) {
    const Mode& xm = x.mode[static_cast<std::size_t>(m)];
    int k = 0;
    while (k < acc.n_modes && !(acc.mode[static_cast<std::size_t>(k)].sigma == xm.sigma &&
                                acc.mode[static_cast<std::size_t>(k)].omega == xm.omega &&
                                acc.mode[static_cast<std::size_t>(k)].general == xm.general &&
                                acc.mode[static_cast<std::size_t>(k)].w2 == xm.w2))
      ++k;
    assert(k < kMaxModes);
    Mode& am = acc.mode[static_cast<std::size_t>(k)];
    if (k == acc.n_modes) {
      am = Mode{};
      take_oscillator(am, xm);
      ++acc.n_modes;
    }
    am.a += s * xm.a;
    am.b += s * xm.b;
    if (xm.general) {
      am.c2 += s * xm.c2;
      am.c3 += s * xm.c3;
    }
    for (int j = 0; j < x.n_sines; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      am.rr[at[jj]] += s * xm.rr[jj];
      am.ri[at[jj]] += s * xm.ri[jj];
    }
  }
}

Wave derivative(const Wave& x) {
  Wave d;
  d.t0 = x.t0;
  double v[2];
  x.eval(x.t0, v, 2);
  d.f0 = v[1];
  d.n_sines = x.n_sines;
  for (int j = 0; j < x.n_sines; ++j) {
    const Sine& xs = x.sine[static_cast<std::size_t>(j)];
    Sine& ds = d.sine[static_cast<std::size_t>(j)];
    ds.w = xs.w;
    ds.ps = -xs.w * xs.pc;
    ds.pc = xs.w * xs.ps;
  }
  d.horizon = x.horizon;
  d.n_modes = x.n_modes;
  for (int m = 0; m < x.n_modes; ++m) {
    const Mode& xm = x.mode[static_cast<std::size_t>(m)];
    Mode& dm = d.mode[static_cast<std::size_t>(m)];
    take_oscillator(dm, xm);
    if (xm.general) {
      dm.a = xm.re[1];
      dm.b = xm.im[1];
      dm.c2 = xm.c3;
      continue;
    }
    // (r G)' = (i w r) G + r exp(z s): the damped term gains r, the resonant one i w r.
    double a = xm.re[1] + xm.rr[0], b = xm.im[1] + xm.ri[0];
    for (std::size_t j = 1; j < static_cast<std::size_t>(x.n_sines); ++j) {
      a += xm.rr[j];
      b += xm.ri[j];
    }
    dm.a = a;
    dm.b = -b;
    for (std::size_t j = 0; j < static_cast<std::size_t>(x.n_sines); ++j) {
      const double w = x.sine[j].w;
      dm.rr[j] = -w * xm.ri[j];
      dm.ri[j] = w * xm.rr[j];
    }
  }
  d.prepare();
  return d;
}

namespace {

// x as a default Wave in every field an oscillator reads or fills (the first mode, the
// load's n sinusoids, the counts and totals; the rest nothing reads past the counts), with
// the one mode of the oscillator (m, c, k): its amplitudes are left to the caller.
void start_oscillator(Wave& x, double t0, double x0, double horizon, int n_sines, double m, double c, double k) {
  reset(x, t0, x0);
  x.horizon = horizon;
  x.mode[0] = Mode{};
  for (int j = 0; j < n_sines; ++j) x.sine[static_cast<std::size_t>(j)] = Sine{};
  const double sigma = 0.5 * (c / m);
  x.mode[0].sigma = sigma;
  x.mode[0].omega = std::sqrt(k / m - sigma * sigma);
  x.n_modes = 1;
}

}  // namespace

Wave oscillator(double t0, double x0, double v0, double m, double c, double k, double f_const, double fs,
                double fc, double w, double horizon) {
  Wave x;
  oscillator_into(x, t0, x0, v0, m, c, k, f_const, fs, fc, w, horizon);
  return x;
}

// The particular solution P sin(w t) + Q cos(w t) of x'' + c_m x' + k_m x = (fs sin(w t) +
// fc cos(w t)) / m, as a Sine (s0, c0 left to prepare()); every oscillator form shares it.
namespace {
Sine particular_sine(double w, double fs, double fc, double m, double k_m, double c_m) {
  const double a = k_m - w * w, b = c_m * w;
  const double det = a * a + b * b;
  Sine sine;
  sine.w = w;
  sine.ps = (a * fs / m + b * fc / m) / det;
  sine.pc = (a * fc / m - b * fs / m) / det;
  return sine;
}
}  // namespace

void oscillator_into(Wave& x, double t0, double x0, double v0, double m, double c, double k, double f_const,
                     double fs, double fc, double w, double horizon) {
  start_oscillator(x, t0, x0, horizon, 1, m, c, k);
  Mode& md = x.mode[0];
  const double wn2 = k / m, two_zeta_wn = c / m, sigma = md.sigma, omega = md.omega;
  const bool forced = fs != 0.0 || fc != 0.0;
  if (forced && std::hypot(sigma, w - omega) < kNearResonance * w) {
    // The load is Re(F exp(i w t)), F = fc - i fs. From rest at t0 it moves the oscillator
    // by Re(F' / m) times the divided difference of exp(p s) over the poles p = i w, z,
    // conj(z) (F' = F exp(i w t0)), which is (G(s) - exp(-sigma s) sin(omega s) / omega) /
    // (i w - conj z): the near-resonant term with r = F' / (m (i w - conj z)), and a sine.
    // The free motion from (x0 - F0 / K, v0) adds the usual damped term.
    x.n_sines = 1;
    x.sine[0].w = w;
    const Complex r = Complex(fc, -fs) * std::polar(1.0, w * t0) / (m * Complex(sigma, w + omega));
    md.a = x0 - f_const / k;
    md.b = (v0 + sigma * md.a - r.real()) / omega;
    md.rr[0] = r.real();
    md.ri[0] = r.imag();
    x.prepare();
    return;
  }
  // Particular solution: f_const / k + P sin(w t) + Q cos(w t).
  double p = 0.0, q = 0.0;
  if (forced) {
    x.n_sines = 1;
    x.sine[0] = particular_sine(w, fs, fc, m, wn2, two_zeta_wn);
    p = x.sine[0].ps;
    q = x.sine[0].pc;
  }
  double sn, cs;
  sin_cos(forced ? w : 0.0, t0, sn, cs);
  const double xp = f_const / k + p * sn + q * cs;
  const double vp = w * (p * cs - q * sn);
  md.a = x0 - xp;
  md.b = (v0 - vp + sigma * md.a) / omega;
  x.prepare();
}

Wave oscillator(double t0, double x0, double v0, double m, double c, double k, const Forcing& load, double horizon) {
  Wave x;
  oscillator_into(x, t0, x0, v0, m, c, k, load, horizon);
  return x;
}

void oscillator_into(Wave& x, double t0, double x0, double v0, double m, double c, double k, const Forcing& load,
                     double horizon) {
  start_oscillator(x, t0, x0, horizon, load.n, m, c, k);
  Mode& md = x.mode[0];
  const double wn2 = k / m, two_zeta_wn = c / m, sigma = md.sigma, omega = md.omega;
  // The polynomial's particular solution alpha + beta (t - t0); then each sinusoid's, whose
  // value and rate at t0 the free motion makes up for. A near-resonant sinusoid's R_mj starts
  // from rest with rate Re(r_j), which the sine term of the free motion takes back.
  const double beta = load.f1 / k, alpha = (load.f0 - c * beta) / k;
  x.lin = beta;
  double xp = alpha, vp = beta, resonant_rate = 0.0;
  x.n_sines = load.n;
  for (std::size_t j = 0; j < static_cast<std::size_t>(load.n); ++j) {
    const double w = load.w[j], fs = load.fs[j], fc = load.fc[j];
    x.sine[j].w = w;
    if (fs == 0.0 && fc == 0.0) continue;
    if (std::hypot(sigma, w - omega) < kNearResonance * w) {
      const Complex r = Complex(fc, -fs) * std::polar(1.0, w * t0) / (m * Complex(sigma, w + omega));
      md.rr[j] = r.real();
      md.ri[j] = r.imag();
      resonant_rate += r.real();
      continue;
    }
    x.sine[j] = particular_sine(w, fs, fc, m, wn2, two_zeta_wn);
    const double p = x.sine[j].ps, q = x.sine[j].pc;
    const double sn = std::sin(w * t0), cs = std::cos(w * t0);
    xp += p * sn + q * cs;
    vp += w * (p * cs - q * sn);
  }
  md.a = x0 - xp;
  md.b = (v0 - vp + sigma * md.a - resonant_rate) / omega;
  x.prepare();
}

bool near_resonance(double m, double c, double k, const Forcing& load) {
  const double sigma = 0.5 * (c / m), w2 = k / m - sigma * sigma;
  if (!(w2 > 0.0)) return false;  // real roots: |i w - lambda| >= w
  const double omega = std::sqrt(w2);
  for (std::size_t j = 0; j < static_cast<std::size_t>(load.n); ++j)
    if ((load.fs[j] != 0.0 || load.fc[j] != 0.0) && std::hypot(sigma, load.w[j] - omega) < kNearResonance * load.w[j])
      return true;
  return false;
}

void general_oscillator_into(Wave& x, double t0, double x0, double v0, double m, double c, double k,
                             const Forcing& load, double horizon) {
  reset(x, t0, x0);
  x.horizon = horizon;
  x.mode[0] = Mode{};
  Mode& md = x.mode[0];
  const double sigma = 0.5 * (c / m), k_m = k / m, w0 = std::sqrt(k_m);
  md.general = true;
  md.sigma = sigma;
  md.k_m = k_m;
  md.w2 = (w0 - sigma) * (w0 + sigma);  // its sign exact near critical damping
  md.omega = std::sqrt(std::abs(md.w2));
  md.fast = md.w2 < 0.0 ? sigma + md.omega : sigma;
  md.slow = md.w2 < 0.0 ? k_m / md.fast : sigma;
  x.n_modes = 1;
  // Each sinusoid's particular solution, as the other oscillators write it; the general
  // mode starts from the state less their value and rate at t0.
  double xp = 0.0, vp = 0.0;
  x.n_sines = load.n;
  for (std::size_t j = 0; j < static_cast<std::size_t>(load.n); ++j) {
    const double w = load.w[j], fs = load.fs[j], fc = load.fc[j];
    x.sine[j] = Sine{};
    x.sine[j].w = w;
    if (fs == 0.0 && fc == 0.0) continue;
    x.sine[j] = particular_sine(w, fs, fc, m, k_m, c / m);
    const double p = x.sine[j].ps, q = x.sine[j].pc;
    const double sn = std::sin(w * t0), cs = std::cos(w * t0);
    xp += p * sn + q * cs;
    vp += w * (p * cs - q * sn);
  }
  md.a = x0 - xp;
  md.b = (v0 - vp) + sigma * md.a;
  md.c2 = load.f0 / m;
  md.c3 = load.f1 / m;
  x.prepare();
}

Wave constant(double t0, double f0) {
  Wave x;
  x.t0 = t0;
  x.f0 = f0;
  return x;
}

void reset(Wave& w, double t0, double f0) {
  w.t0 = t0;
  w.f0 = f0;
  w.lin = 0.0;
  w.n_sines = 0;
  w.n_modes = 0;
  w.horizon = std::numeric_limits<double>::infinity();
  w.any_resonant = false;
  w.pulse_envelope.fill(0.0);
}

}  // namespace pb::event_driven
