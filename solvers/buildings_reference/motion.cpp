#include "solvers/buildings_reference/motion.hpp"

#include <algorithm>
#include <cmath>

namespace pb::buildings {

namespace {

// exp(x + i y) - 1 to the round-off of its own size: expm1 and, for 1 - cos y, sin^2 / (1 + cos)
// where cos y > 0 (no cancellation near y = 0).
cplx expm1c(double x, double y) {
  const double em = std::expm1(x), sn = std::sin(y), cs = std::cos(y);
  const double vers = cs > 0.0 ? sn * sn / (1.0 + cs) : 1.0 - cs;
  return {em * cs - vers, (1.0 + em) * sn};
}

// Re(a b) without forming the product's imaginary part.
double re_mul(cplx a, cplx b) { return a.real() * b.real() - a.imag() * b.imag(); }

}  // namespace

void Motion::reserve(int n_floors, int n_contacts) {
  n_floors_ = n_floors;
  n_contacts_ = n_contacts;
  n_q_ = 2 * n_floors + n_contacts;
  k_max_ = 2 * n_floors;  // at most two roots per floor (overdamped modes)
  const auto k = static_cast<std::size_t>(k_max_), q = static_cast<std::size_t>(n_q_);
  const auto j = static_cast<std::size_t>(kMaxSinusoids);
  lambda_.resize(k);
  weight_.resize(k);
  res_.resize(k * j * 2);
  lpow_.resize(k);
  lmod_.resize(k);
  rho_.resize(q * k);
  a_.resize(q * k);
  abs_a_.resize(q * k);
  z_.resize(q * j);
  abs_z_.resize(q * j);
  r_.resize(q * k * j * 2);
  abs_r_.resize(q * k * j * 2);
  f0_.resize(q);
  lin_.resize(q);
  q0_.resize(static_cast<std::size_t>(n_floors));
  qd0_.resize(static_cast<std::size_t>(n_floors));
  c0_.resize(k);
  lin_mode_.resize(k);
  h_mode_.resize(k);
  x_mode_.resize(k);
  em_.resize(k);
  e_res_.resize(k * j * 2);
  decay_.resize(k);
}

void Motion::build(const BuildingModel& md, const Reduced& r, const Modal& mo, const double* u, const double* v,
                   const double* g, const LoadPiece& piece, double t0, double horizon) {
  t0_ = t0;
  horizon_ = horizon;
  basis_ok_ = decay_ok_ = false;
  n_k_ = mo.n;
  n_j_ = piece.n_waves;
  n_r_ = 0;
  // The load from t0: p0 + p1 s + sum_j Re(F_j e^(i w_j t)), F = c - i s.
  const double p0 = piece.slope == 0.0 ? piece.value : piece.value + piece.slope * (t0 - piece.start);
  const double p1 = piece.slope;
  std::array<cplx, kMaxSinusoids> f{}, rot{};  // F_j, and e^(i w_j t0)
  fastest_ = 0.0;
  for (int j = 0; j < n_j_; ++j) {
    const Sinusoid& s = piece.waves[static_cast<std::size_t>(j)];
    w_[static_cast<std::size_t>(j)] = s.w;
    f[static_cast<std::size_t>(j)] = cplx(s.c, -s.s);
    rot[static_cast<std::size_t>(j)] = cplx(std::cos(s.w * t0), std::sin(s.w * t0));
    fastest_ = std::max(fastest_, s.w);
  }
  r.reduce(u, v, q0_.data(), qd0_.data());
  for (int k = 0; k < n_k_; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const cplx lam = mo.lambda(k);
    lambda_[kk] = lam;
    weight_[kk] = mo.weight(k);
    fastest_ = std::max(fastest_, std::abs(lam));
    lpow_[kk][0] = 1.0;
    lmod_[kk][0] = 1.0;
    for (int d = 1; d <= kMaxOrder; ++d) {
      lpow_[kk][static_cast<std::size_t>(d)] = lpow_[kk][static_cast<std::size_t>(d - 1)] * lam;
      lmod_[kk][static_cast<std::size_t>(d)] = std::abs(lpow_[kk][static_cast<std::size_t>(d)]);
    }
    cplx c0 = 0.0;
    for (int c = 0; c < r.n; ++c) c0 += mo.in_q(k, c) * q0_[static_cast<std::size_t>(c)] + mo.in_v(k, c) * qd0_[static_cast<std::size_t>(c)];
    // The polynomial part A + B s: B lambda + alpha p1 = 0, A lambda + gamma + alpha p0 = B.
    const cplx alpha = mo.alpha(k), gamma = mo.gamma(k);
    const cplx b = -alpha * p1 / lam;
    const cplx a = (b - gamma - alpha * p0) / lam;
    cplx part = a;
    for (int j = 0; j < n_j_; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      const double w = w_[jj];
      for (int sign = 0; sign < 2; ++sign) {
        // Re(F e^(i w t)) = (F e^(i w t) + conj(F) e^(-i w t)) / 2.
        const cplx at(0.0, sign == 0 ? w : -w);
        const cplx fs = sign == 0 ? f[jj] : std::conj(f[jj]);
        const cplx phase = sign == 0 ? rot[jj] : std::conj(rot[jj]);
        const cplx d = at - lam;
        cplx& xe = x_mode_[kk][2 * jj + static_cast<std::size_t>(sign)];
        if (std::abs(d) < kNearResonance * w) {
          Resonant& rs = res_[static_cast<std::size_t>(n_r_++)];
          rs.mode = k;
          rs.sine = j;
          rs.a = at;
          rs.coef = 0.5 * alpha * fs * phase;
          const double span = horizon - t0;
          const double grow = lam.real() > 0.0 ? std::exp(lam.real() * span) : 1.0;
          rs.bound = grow * std::min(2.0 / std::abs(d), span);
          rs.a_pow[0] = 1.0;
          rs.s_sum[0] = 0.0;
          for (std::size_t o = 1; o <= kMaxOrder; ++o) {
            rs.a_pow[o] = rs.a_pow[o - 1] * at;
            // S_o = a S_(o-1) + lambda^(o-1)
            rs.s_sum[o] = at * rs.s_sum[o - 1] + lpow_[kk][o - 1];
          }
          xe = 0.0;
        } else {
          xe = 0.5 * alpha * fs / d * phase;
          part += xe;
        }
      }
    }
    c0_[kk] = c0;
    lin_mode_[kk] = b;
    h_mode_[kk] = c0 - part;
  }
  // Modal rows of the quantities.
  const int nf = n_floors_;
  for (int k = 0; k < n_k_; ++k) {
    for (int i = 0; i < nf; ++i) rho(floor(i), k) = mo.shape(r.cluster[static_cast<std::size_t>(i)], k);
    for (int i = 0; i < nf; ++i) {
      const bool bottom = md.first[static_cast<std::size_t>(md.building_of[static_cast<std::size_t>(i)])] == i;
      rho(drift(i), k) = bottom ? rho(floor(i), k) : rho(floor(i), k) - rho(floor(i - 1), k);
    }
    for (int j = 0; j < n_contacts_; ++j) {
      const FloorContact& fc = md.contacts[static_cast<std::size_t>(j)];
      if (!r.stuck[static_cast<std::size_t>(j)]) {
        rho(contact(j), k) = rho(floor(fc.i_right), k) - rho(floor(fc.i_left), k);
      } else {
        cplx x = 0.0;
        for (int c = 0; c < r.n; ++c) x += (r.Lq(j, c) + lambda_[static_cast<std::size_t>(k)] * r.Lv(j, c)) * mo.shape(c, k);
        rho(contact(j), k) = x;
      }
    }
  }
  // Each quantity's terms; its value at t0 from the state, and (a displacement) its rate too.
  for (int q = 0; q < n_q_; ++q) {
    const auto qq = static_cast<std::size_t>(q);
    double lin = 0.0;
    std::array<cplx, kMaxSinusoids> z{};
    for (int k = 0; k < n_k_; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      const cplx p = weight_[kk] * rho(q, k);
      lin += re_mul(p, lin_mode_[kk]);
      const cplx a = p * h_mode_[kk];
      a_[qq * static_cast<std::size_t>(k_max_) + kk] = a;
      abs_a_[qq * static_cast<std::size_t>(k_max_) + kk] = std::abs(a);
      for (std::size_t j = 0; j < static_cast<std::size_t>(n_j_); ++j)
        z[j] += p * x_mode_[kk][2 * j] + std::conj(p * x_mode_[kk][2 * j + 1]);
    }
    for (std::size_t j = 0; j < static_cast<std::size_t>(n_j_); ++j) {
      z_[qq * kMaxSinusoids + j] = z[j];
      abs_z_[qq * kMaxSinusoids + j] = std::abs(z[j]);
    }
    const std::size_t r_at = qq * static_cast<std::size_t>(k_max_ * kMaxSinusoids * 2);
    for (int e = 0; e < n_r_; ++e) {
      const Resonant& rs = res_[static_cast<std::size_t>(e)];
      const cplx x = weight_[static_cast<std::size_t>(rs.mode)] * rho(q, rs.mode) * rs.coef;
      r_[r_at + static_cast<std::size_t>(e)] = x;
      abs_r_[r_at + static_cast<std::size_t>(e)] = std::abs(x);
    }
    double value, rate;
    bool displacement = true;
    if (q < nf) {
      value = u[q];
      rate = v[q];
    } else if (q < 2 * nf) {
      const int i = q - nf;
      const bool bottom = md.first[static_cast<std::size_t>(md.building_of[static_cast<std::size_t>(i)])] == i;
      value = bottom ? u[i] : u[i] - u[i - 1];
      rate = bottom ? v[i] : v[i] - v[i - 1];
    } else {
      const int j = q - 2 * nf;
      const FloorContact& fc = md.contacts[static_cast<std::size_t>(j)];
      if (!r.stuck[static_cast<std::size_t>(j)]) {
        value = g[j];
        rate = v[fc.i_right] - v[fc.i_left];
      } else {
        displacement = false;
        value = r.L0(j);
        for (int c = 0; c < r.n; ++c)
          value += r.Lq(j, c) * q0_[static_cast<std::size_t>(c)] + r.Lv(j, c) * qd0_[static_cast<std::size_t>(c)];
        rate = 0.0;
      }
    }
    f0_[qq] = value;
    if (displacement) {
      // The rate the terms give, to the state's: they differ by the modes' round-off, and a gap
      // that has just opened must start at its own rate. (E_r'(0) = 1.)
      double terms = lin;
      for (std::size_t j = 0; j < static_cast<std::size_t>(n_j_); ++j) terms -= z[j].imag() * w_[j];
      for (int k = 0; k < n_k_; ++k)
        terms += re_mul(a_[qq * static_cast<std::size_t>(k_max_) + static_cast<std::size_t>(k)], lambda_[static_cast<std::size_t>(k)]);
      for (int e = 0; e < n_r_; ++e) terms += r_[r_at + static_cast<std::size_t>(e)].real();
      lin += rate - terms;
    }
    lin_[qq] = lin;
  }
}

void Motion::basis(double t) {
  if (basis_ok_ && t == basis_t_) return;
  basis_ok_ = true;
  basis_t_ = t;
  const double s = t - t0_;
  for (std::size_t k = 0; k < static_cast<std::size_t>(n_k_); ++k) {
    const cplx lam = lambda_[k];
    const cplx em = expm1c(lam.real() * s, lam.imag() * s);
    const cplx e = 1.0 + em;
    em_[k][0] = em;
    for (std::size_t d = 1; d <= kMaxOrder; ++d) em_[k][d] = lpow_[k][d] * e;
  }
  for (std::size_t j = 0; j < static_cast<std::size_t>(n_j_); ++j) {
    const double y = w_[j] * s, sn = std::sin(y), cs = std::cos(y);
    const double vers = cs > 0.0 ? sn * sn / (1.0 + cs) : 1.0 - cs;
    ew_[j][0] = cplx(-vers, sn);
    const cplx e(cs, sn), iw(0.0, w_[j]);
    cplx p = e;
    for (std::size_t d = 1; d <= kMaxOrder; ++d) {
      p *= iw;
      ew_[j][d] = p;
    }
  }
  for (std::size_t r = 0; r < static_cast<std::size_t>(n_r_); ++r) {
    const Resonant& rs = res_[r];
    const auto k = static_cast<std::size_t>(rs.mode);
    const cplx e = 1.0 + em_[k][0];
    const cplx d = rs.a - lambda_[k];
    // E = exp(lambda s) (exp(d s) - 1) / d: exact at d = 0 (s exp(lambda s)) and next to it.
    e_res_[r] = d == 0.0 ? s * e : e * expm1c(d.real() * s, d.imag() * s) / d;
  }
}

void Motion::decays(double t) {
  if (decay_ok_ && t == decay_t_) return;
  decay_ok_ = true;
  decay_t_ = t;
  // A root on the right half-plane (round-off of an undamped one) grows until the horizon.
  for (std::size_t k = 0; k < static_cast<std::size_t>(n_k_); ++k) {
    const double re = lambda_[k].real();
    decay_[k] = re > 0.0 ? std::exp(re * (horizon_ - t0_)) : std::exp(re * std::max(t - t0_, 0.0));
  }
}

void Motion::eval(int q, double t, double* out, int nd) {
  basis(t);
  const auto qq = static_cast<std::size_t>(q);
  const cplx* a = &a_[qq * static_cast<std::size_t>(k_max_)];
  const cplx* z = &z_[qq * kMaxSinusoids];
  const cplx* rr = &r_[qq * static_cast<std::size_t>(k_max_ * kMaxSinusoids * 2)];
  const double s = t - t0_;
  for (int d = 0; d < nd; ++d) {
    const auto dd = static_cast<std::size_t>(d);
    double sum = 0.0;
    for (std::size_t j = 0; j < static_cast<std::size_t>(n_j_); ++j) sum += re_mul(z[j], ew_[j][dd]);
    for (std::size_t k = 0; k < static_cast<std::size_t>(n_k_); ++k) sum += re_mul(a[k], em_[k][dd]);
    for (std::size_t r = 0; r < static_cast<std::size_t>(n_r_); ++r) {
      const Resonant& rs = res_[r];
      cplx e = e_res_[r];
      if (d > 0) e = rs.a_pow[dd] * e + rs.s_sum[dd] * (1.0 + em_[static_cast<std::size_t>(rs.mode)][0]);
      sum += re_mul(rr[r], e);
    }
    if (d == 0)
      out[0] = f0_[qq] + (lin_[qq] * s + sum);
    else
      out[d] = d == 1 ? lin_[qq] + sum : sum;
  }
}

void Motion::bounds(int q, double t, double* b) {
  decays(t);
  const auto qq = static_cast<std::size_t>(q);
  const double* a = &abs_a_[qq * static_cast<std::size_t>(k_max_)];
  const double* z = &abs_z_[qq * kMaxSinusoids];
  const double* rr = &abs_r_[qq * static_cast<std::size_t>(k_max_ * kMaxSinusoids * 2)];
  const double lin = std::abs(lin_[qq]);
  for (std::size_t d = 0; d <= kMaxOrder; ++d) {
    double sum = d == 0 ? 0.5 * lin * (horizon_ - t0_) : d == 1 ? lin : 0.0;
    for (std::size_t j = 0; j < static_cast<std::size_t>(n_j_); ++j) sum += z[j] * std::pow(w_[j], static_cast<double>(d));
    for (std::size_t k = 0; k < static_cast<std::size_t>(n_k_); ++k) sum += a[k] * lmod_[k][d] * decay_[k];
    for (std::size_t r = 0; r < static_cast<std::size_t>(n_r_); ++r) {
      const Resonant& rs = res_[r];
      sum += rr[r] * (std::abs(rs.a_pow[d]) * rs.bound + std::abs(rs.s_sum[d]) * decay_[static_cast<std::size_t>(rs.mode)]);
    }
    b[d] = sum;
  }
}

double Motion::mean(int q) const {
  const auto qq = static_cast<std::size_t>(q);
  double m = f0_[qq] + 0.5 * lin_[qq] * (horizon_ - t0_);
  for (std::size_t j = 0; j < static_cast<std::size_t>(n_j_); ++j) m -= z_[qq * kMaxSinusoids + j].real();
  for (std::size_t k = 0; k < static_cast<std::size_t>(n_k_); ++k) m -= a_[qq * static_cast<std::size_t>(k_max_) + k].real();
  return m;
}

}  // namespace pb::buildings
