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

// |a| without hypot's care for overflow (coefficients of motions far from it), a third of its cost.
double modulus(cplx a) { return std::sqrt(a.real() * a.real() + a.imag() * a.imag()); }

// Past this |z|, exp(z) - 1 loses nothing against its own size (|exp(z) - 1| > 0.39 |z|...):
// the increment is formed from exp(z) itself, without a second transcendental.
constexpr double kSmallArgument = 0.5;

}  // namespace

void Motion::reserve(int n_floors, int n_contacts) {
  n_floors_ = n_floors;
  n_contacts_ = n_contacts;
  n_q_ = 2 * n_floors + n_contacts;
  k_max_ = 2 * n_floors;  // at most two roots per floor (overdamped modes)
  stride_ = static_cast<std::size_t>(k_max_) + kMaxSinusoids;
  const auto k = static_cast<std::size_t>(k_max_), q = static_cast<std::size_t>(n_q_);
  const auto j = static_cast<std::size_t>(kMaxSinusoids);
  rate_.resize(stride_);
  pow_.resize(stride_);
  mod_.resize(stride_);
  weight_.resize(k);
  res_.resize(k * j * 2);
  rho_.resize(q * k);
  coef_.resize(q * stride_);
  coef_rate_.resize(q * stride_);
  r_.resize(q * k * j * 2);
  f0_.resize(q);
  lin_.resize(q);
  rate0_.resize(q);
  mean_.resize(q);
  bound_const_.resize(q * (kMaxOrder + 1));
  bound_env_.resize(q * (kMaxOrder + 1) * k);
  coef_abs_.resize(q * stride_);
  res4_.resize(q);
  q0_.resize(static_cast<std::size_t>(n_floors));
  qd0_.resize(static_cast<std::size_t>(n_floors));
  lin_mode_.resize(k);
  modulus_.resize(stride_);
  h_mode_.resize(k);
  x_mode_.resize(k);
  for (std::vector<cplx>& b : basis_) b.resize(stride_);
  exp_.resize(stride_);
  e_res_.resize(k * j * 2);
  v_res_.resize(k * j * 2);
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
  fastest_ = 0.0;
  take_load(piece);
  r.reduce(u, v, q0_.data(), qd0_.data());
  for (int k = 0; k < n_k_; ++k) solve_mode(r, mo, k);
  fill_rows(md, r, mo);
  for (int q = 0; q < n_q_; ++q) fill_terms(md, r, q, u, v, g);
}

void Motion::set_powers(std::size_t m, cplx x) {
  rate_[m] = x;
  pow_[m][0] = 1.0;
  mod_[m][0] = 1.0;
  const double modulus = std::abs(x);
  for (std::size_t d = 1; d <= kMaxOrder; ++d) {
    pow_[m][d] = pow_[m][d - 1] * x;
    mod_[m][d] = mod_[m][d - 1] * modulus;
  }
  fastest_ = std::max(fastest_, modulus);
}

// The load from t0: p0 + p1 s + sum_j Re(F_j e^(i w_j t)), F = c - i s; its sinusoids are the
// terms after the modes.
void Motion::take_load(const LoadPiece& piece) {
  p0_ = piece.slope == 0.0 ? piece.value : piece.value + piece.slope * (t0_ - piece.start);
  p1_ = piece.slope;
  for (int j = 0; j < n_j_; ++j) {
    const auto jj = static_cast<std::size_t>(j);
    const Sinusoid& s = piece.waves[jj];
    load_f_[jj] = cplx(s.c, -s.s);
    load_rot_[jj] = cplx(std::cos(s.w * t0_), std::sin(s.w * t0_));
    set_powers(static_cast<std::size_t>(n_k_) + jj, cplx(0.0, s.w));
  }
}

// Mode k's closed form from the reduced state q0_, qd0_: its polynomial part A + B s, each
// sinusoid's particular part X e^(+-i w t) or, near resonance, its secular term R E, and the
// free part H e^(lambda s) that fits c(t0).
void Motion::solve_mode(const Reduced& r, const Modal& mo, int k) {
  const auto kk = static_cast<std::size_t>(k);
  const cplx lam = mo.lambda(k);
  set_powers(kk, lam);
  weight_[kk] = mo.weight(k);
  cplx c0 = 0.0;
  for (int c = 0; c < r.n; ++c)
    c0 += mo.in_q(k, c) * q0_[static_cast<std::size_t>(c)] + mo.in_v(k, c) * qd0_[static_cast<std::size_t>(c)];
  // B lambda + alpha p1 = 0, A lambda + gamma + alpha p0 = B.
  const cplx alpha = mo.alpha(k), gamma = mo.gamma(k);
  const cplx b = -alpha * p1_ / lam;
  cplx part = (b - gamma - alpha * p0_) / lam;
  const double span = horizon_ - t0_;
  for (std::size_t jj = 0; jj < static_cast<std::size_t>(n_j_); ++jj) {
    const double w = rate_[static_cast<std::size_t>(n_k_) + jj].imag();
    for (int sign = 0; sign < 2; ++sign) {
      // Re(F e^(i w t)) = (F e^(i w t) + conj(F) e^(-i w t)) / 2.
      const cplx at(0.0, sign == 0 ? w : -w);
      const cplx fs = sign == 0 ? load_f_[jj] : std::conj(load_f_[jj]);
      const cplx phase = sign == 0 ? load_rot_[jj] : std::conj(load_rot_[jj]);
      const cplx d = at - lam;
      cplx& xe = x_mode_[kk][2 * jj + static_cast<std::size_t>(sign)];
      if (std::abs(d) < kNearResonance * w) {
        Resonant& rs = res_[static_cast<std::size_t>(n_r_++)];
        rs.mode = k;
        rs.sine = static_cast<int>(jj);
        rs.a = at;
        rs.coef = 0.5 * alpha * fs * phase;
        // |E| <= min(2 / |d|, s) times the mode's largest growth (none, but for round-off).
        const double grow = lam.real() > 0.0 ? std::exp(lam.real() * span) : 1.0;
        rs.bound = grow * std::min(2.0 / std::abs(d), span);
        rs.a_pow[0] = 1.0;
        rs.s_sum[0] = 0.0;
        for (std::size_t o = 1; o <= kMaxOrder; ++o) {
          rs.a_pow[o] = rs.a_pow[o - 1] * at;
          rs.s_sum[o] = at * rs.s_sum[o - 1] + pow_[kk][o - 1];  // S_o = a S_(o-1) + lambda^(o-1)
        }
        xe = 0.0;
      } else {
        xe = 0.5 * alpha * fs / d * phase;
        part += xe;
      }
    }
  }
  lin_mode_[kk] = b;
  h_mode_[kk] = c0 - part;
}

// The quantities' modal rows: a floor's is its cluster's shape, a drift and a gap differences of
// floors', a stuck contact's force (Lq + lambda Lv) shape (q' = lambda q mode by mode).
void Motion::fill_rows(const BuildingModel& md, const Reduced& r, const Modal& mo) {
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
        const cplx lam = rate_[static_cast<std::size_t>(k)];
        for (int c = 0; c < r.n; ++c) x += (r.Lq(j, c) + lam * r.Lv(j, c)) * mo.shape(c, k);
        rho(contact(j), k) = x;
      }
    }
  }
}

// Quantity q's value and rate at t0 from the state: a stuck contact's force from the reduced
// state (its rate is not known there: *rate is left, false returned).
bool Motion::state_value(const BuildingModel& md, const Reduced& r, int q, const double* u, const double* v,
                         const double* g, double& value, double& rate) const {
  const int nf = n_floors_;
  if (q < nf) {
    value = u[q];
    rate = v[q];
    return true;
  }
  if (q < 2 * nf) {
    const int i = q - nf;
    const bool bottom = md.first[static_cast<std::size_t>(md.building_of[static_cast<std::size_t>(i)])] == i;
    value = bottom ? u[i] : u[i] - u[i - 1];
    rate = bottom ? v[i] : v[i] - v[i - 1];
    return true;
  }
  const int j = q - 2 * nf;
  const FloorContact& fc = md.contacts[static_cast<std::size_t>(j)];
  if (!r.stuck[static_cast<std::size_t>(j)]) {
    value = g[j];
    rate = v[fc.i_right] - v[fc.i_left];
    return true;
  }
  value = r.L0(j);
  for (int c = 0; c < r.n; ++c)
    value += r.Lq(j, c) * q0_[static_cast<std::size_t>(c)] + r.Lv(j, c) * qd0_[static_cast<std::size_t>(c)];
  return false;
}

// Quantity q's terms, its value at t0 from the state, and (a displacement) its rate too; its
// mean and the parts of its bounds.
void Motion::fill_terms(const BuildingModel& md, const Reduced& r, int q, const double* u, const double* v,
                        const double* g) {
  const auto qq = static_cast<std::size_t>(q);
  const std::size_t nt = terms(), nres = static_cast<std::size_t>(n_r_);
  cplx* cf = &coef_[qq * stride_];
  cplx* rr = &r_[qq * static_cast<std::size_t>(k_max_ * kMaxSinusoids * 2)];
  double lin = 0.0;
  for (std::size_t j = 0; j < static_cast<std::size_t>(n_j_); ++j) cf[static_cast<std::size_t>(n_k_) + j] = 0.0;
  for (int k = 0; k < n_k_; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const cplx p = weight_[kk] * rho(q, k);
    lin += re_mul(p, lin_mode_[kk]);
    cf[kk] = p * h_mode_[kk];
    for (std::size_t j = 0; j < static_cast<std::size_t>(n_j_); ++j)
      cf[static_cast<std::size_t>(n_k_) + j] += p * x_mode_[kk][2 * j] + std::conj(p * x_mode_[kk][2 * j + 1]);
  }
  for (std::size_t e = 0; e < nres; ++e) {
    const Resonant& rs = res_[e];
    rr[e] = weight_[static_cast<std::size_t>(rs.mode)] * rho(q, rs.mode) * rs.coef;
  }
  double value = 0.0, rate = 0.0;
  const bool displacement = state_value(md, r, q, u, v, g, value, rate);
  f0_[qq] = value;
  // The rate the terms give (E_r'(0) = 1); a displacement's is made the state's: they differ
  // by the modes' round-off, and a gap that has just opened must start at its own rate.
  double terms_rate = lin;
  cplx* cv = &coef_rate_[qq * stride_];
  for (std::size_t m = 0; m < nt; ++m) {
    cv[m] = cf[m] * rate_[m];
    terms_rate += cv[m].real();
  }
  for (std::size_t e = 0; e < nres; ++e) terms_rate += rr[e].real();
  if (displacement) lin += rate - terms_rate;
  rate0_[qq] = displacement ? rate : terms_rate;
  lin_[qq] = lin;
  // The mean (a linear term at its value halfway to the horizon) and the bounds' parts.
  const double span = horizon_ - t0_;
  double mean = value + 0.5 * lin * span;
  for (std::size_t m = 0; m < nt; ++m) mean -= cf[m].real();
  mean_[qq] = mean;
  fill_bounds(q, lin, span);
}

// bounds()' parts of quantity q: per order a constant (the linear term, the sinusoids, the
// near-resonant terms' growth) and per mode the coefficient of its decay; hermite_error()'s
// moduli.
void Motion::fill_bounds(int q, double lin, double span) {
  const auto qq = static_cast<std::size_t>(q);
  const std::size_t nt = terms(), nres = static_cast<std::size_t>(n_r_);
  const cplx* cf = &coef_[qq * stride_];
  const cplx* rr = &r_[qq * static_cast<std::size_t>(k_max_ * kMaxSinusoids * 2)];
  double* bc = &bound_const_[qq * (kMaxOrder + 1)];
  double* env = &bound_env_[qq * (kMaxOrder + 1) * static_cast<std::size_t>(k_max_)];
  for (std::size_t m = 0; m < nt; ++m) modulus_[m] = coef_abs_[qq * stride_ + m] = modulus(cf[m]);
  res4_[qq] = 0.0;
  for (std::size_t d = 0; d <= kMaxOrder; ++d) {
    double c = d == 0 ? 0.5 * std::abs(lin) * span : d == 1 ? std::abs(lin) : 0.0;
    for (std::size_t m = static_cast<std::size_t>(n_k_); m < nt; ++m) c += modulus_[m] * mod_[m][d];
    double* e = env + d * static_cast<std::size_t>(k_max_);
    for (std::size_t k = 0; k < static_cast<std::size_t>(n_k_); ++k) e[k] = modulus_[k] * mod_[k][d];
    // A near-resonant term: |E^(d)| <= |a|^d max|E| + |S_d| exp(Re lambda s).
    for (std::size_t x = 0; x < nres; ++x) {
      const Resonant& rs = res_[x];
      const double ar = modulus(rr[x]);
      c += ar * std::abs(rs.a_pow[d]) * rs.bound;
      e[static_cast<std::size_t>(rs.mode)] += ar * std::abs(rs.s_sum[d]);
      // hermite_error's: the modes' decay at their largest (1, or the growth to the horizon).
      if (d == kMaxOrder)
        res4_[qq] += ar * (std::abs(rs.a_pow[d]) * rs.bound +
                           std::abs(rs.s_sum[d]) * std::max(1.0, std::exp(rate_[static_cast<std::size_t>(rs.mode)].real() * span)));
    }
    bc[d] = c;
  }
}

void Motion::basis(double t, int nd) {
  if (basis_ok_ && t == basis_t_) {
    if (nd <= basis_nd_) return;
    // Higher orders at the same t: rate^d exp(rate s).
    for (std::size_t m = 0; m < terms(); ++m)
      for (auto d = static_cast<std::size_t>(basis_nd_); d < static_cast<std::size_t>(nd); ++d)
        basis_[d][m] = pow_[m][d] * exp_[m];
    basis_nd_ = nd;
    return;
  }
  basis_ok_ = true;
  basis_t_ = t;
  basis_nd_ = std::max(nd, 2);
  const auto top = static_cast<std::size_t>(basis_nd_);
  const double s = t - t0_;
  const std::size_t nt = terms();
  if (s == 0.0) {  // the segment's start: no transcendental to take
    for (std::size_t m = 0; m < nt; ++m) {
      basis_[0][m] = 0.0;
      exp_[m] = 1.0;
      for (std::size_t d = 1; d < top; ++d) basis_[d][m] = pow_[m][d];
    }
    for (std::size_t r = 0; r < static_cast<std::size_t>(n_r_); ++r) e_res_[r] = 0.0;
    return;
  }
  for (std::size_t m = 0; m < nt; ++m) {
    const cplx x = rate_[m] * s;
    const double mag = x.real() == 0.0 ? 1.0 : std::exp(x.real()), sn = std::sin(x.imag()), cs = std::cos(x.imag());
    const cplx e(mag * cs, mag * sn);
    exp_[m] = e;
    basis_[0][m] = std::abs(x.real()) + std::abs(x.imag()) < kSmallArgument ? expm1c(x.real(), x.imag()) : e - 1.0;
    for (std::size_t d = 1; d < top; ++d) basis_[d][m] = pow_[m][d] * e;
  }
  for (std::size_t r = 0; r < static_cast<std::size_t>(n_r_); ++r) {
    const Resonant& rs = res_[r];
    const auto k = static_cast<std::size_t>(rs.mode);
    const cplx e = basis_[0][k] + 1.0;
    const cplx d = rs.a - rate_[k];
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
    const double re = rate_[k].real();
    decay_[k] = re > 0.0 ? std::exp(re * (horizon_ - t0_)) : std::exp(re * std::max(t - t0_, 0.0));
  }
}

void Motion::eval(int q, double t, double* out, int nd) {
  basis(t, nd);
  const auto qq = static_cast<std::size_t>(q);
  const cplx* cf = &coef_[qq * stride_];
  const cplx* rr = &r_[qq * static_cast<std::size_t>(k_max_ * kMaxSinusoids * 2)];
  const std::size_t nt = terms();
  const double s = t - t0_;
  for (int d = 0; d < nd; ++d) {
    const auto dd = static_cast<std::size_t>(d);
    const cplx* b = basis_[dd].data();
    double sum = 0.0;
    for (std::size_t m = 0; m < nt; ++m) sum += re_mul(cf[m], b[m]);
    for (std::size_t r = 0; r < static_cast<std::size_t>(n_r_); ++r) {
      const Resonant& rs = res_[r];
      cplx e = e_res_[r];
      if (d > 0) e = rs.a_pow[dd] * e + rs.s_sum[dd] * (1.0 + basis_[0][static_cast<std::size_t>(rs.mode)]);
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
  const double* bc = &bound_const_[qq * (kMaxOrder + 1)];
  const double* env = &bound_env_[qq * (kMaxOrder + 1) * static_cast<std::size_t>(k_max_)];
  const auto nk = static_cast<std::size_t>(n_k_);
  for (std::size_t d = 0; d <= kMaxOrder; ++d) {
    const double* e = env + d * static_cast<std::size_t>(k_max_);
    double sum = bc[d];
    for (std::size_t k = 0; k < nk; ++k) sum += e[k] * decay_[k];
    b[d] = sum;
  }
}

double Motion::mean(int q) const { return mean_[static_cast<std::size_t>(q)]; }

double Motion::hermite_error(int q, double t, double h) {
  decays(t);
  const auto qq = static_cast<std::size_t>(q);
  const double* a = &coef_abs_[qq * stride_];
  const double h4 = h * h * h * h / 384.0;
  double sum = res4_[qq] * h4;
  const std::size_t nt = terms(), nk = static_cast<std::size_t>(n_k_);
  for (std::size_t m = 0; m < nt; ++m) {
    const double amp = m < nk ? a[m] * decay_[m] : a[m];
    sum += amp * std::min(mod_[m][kMaxOrder] * h4, 2.0 + (8.0 / 27.0) * mod_[m][1] * h);
  }
  return sum;
}

void Motion::exp_factors(double s, cplx* modes, cplx* sines) const {
  for (std::size_t m = 0; m < terms(); ++m) {
    const cplx x = rate_[m] * s;
    const cplx e = std::exp(x.real()) * cplx(std::cos(x.imag()), std::sin(x.imag()));
    if (m < static_cast<std::size_t>(n_k_))
      modes[m] = e;
    else
      sines[m - static_cast<std::size_t>(n_k_)] = e;
  }
}

void Motion::floor_velocities(double t, const cplx* modes, const cplx* sines, double* v) {
  const double s = t - t0_;
  // The near-resonant terms' E'(s) = a E + exp(lambda s), E evaluated (they are few).
  const auto nr = static_cast<std::size_t>(n_r_);
  for (std::size_t r = 0; r < nr; ++r) {
    const Resonant& rs = res_[r];
    const cplx e = modes[static_cast<std::size_t>(rs.mode)];
    const cplx d = rs.a - rate_[static_cast<std::size_t>(rs.mode)];
    const cplx big_e = d == 0.0 ? s * e : e * expm1c(d.real() * s, d.imag() * s) / d;
    v_res_[r] = rs.a * big_e + e;
  }
  const auto nk = static_cast<std::size_t>(n_k_), nj = static_cast<std::size_t>(n_j_);
  for (int i = 0; i < n_floors_; ++i) {
    const auto qq = static_cast<std::size_t>(floor(i));
    const cplx* rr = &r_[qq * static_cast<std::size_t>(k_max_ * kMaxSinusoids * 2)];
    double sum = lin_[qq];
    const cplx* cv = &coef_rate_[qq * stride_];
    for (std::size_t k = 0; k < nk; ++k) sum += re_mul(cv[k], modes[k]);
    for (std::size_t j = 0; j < nj; ++j) sum += re_mul(cv[nk + j], sines[j]);
    for (std::size_t r = 0; r < nr; ++r) sum += re_mul(rr[r], v_res_[r]);
    v[i] = sum;
  }
}

}  // namespace pb::buildings
