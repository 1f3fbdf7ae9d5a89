#pragma once
// The closed form of every tracked quantity between two events (DERIVATION.md §3).
//
// On one piece of the load, a_g(t) = p0 + p1 (t - t0) + sum_j Re(F_j exp(i w_j t)), each
// modal coordinate of the stuck set's system (stuck.hpp) solves c' = lambda c + gamma +
// alpha a_g(t):
//
//   c(t0 + s) = A + B s + sum_j,+- X exp(+-i w_j t) + H exp(lambda s)        (plain), or
//             ... + R E(+-i w_j, lambda; s),  E(a, l; s) = (exp(a s) - exp(l s)) / (a - l)
//
// where a sinusoid lies within kNearResonance w_j of the mode's root: E is the forced
// response from rest, exact at resonance (E = s exp(l s), the secular t sin, t cos) and
// next to it. Every tracked quantity (a floor's displacement, a storey's drift, an open
// contact's gap, a stuck contact's force) is a real linear combination of the modal
// coordinates, and is stored as its value at t0 plus increments:
//
//   f(t0 + s) = f0 + lin s + sum_j Re(Z_j (exp(i w_j s) - 1)) + sum_k Re(a_k (exp(lambda_k s) - 1))
//               + sum_r Re(r_r E_r(s)),
//
// each increment computed from expm1 and half-angle forms, so that a gap that starts at zero
// is resolved to the round-off of its own size, not of the displacements it is made of.
// Every derivative is of the same form, and |f^(d)| is bounded over [t, horizon] from the
// moduli of the coefficients (the damped terms only decay): the searches rest on these bounds.
//
// Sized once (reserve) for the scene; building and evaluating allocate nothing.

#include <array>
#include <complex>
#include <vector>

#include "cases/buildings.hpp"
#include "cases/load.hpp"
#include "solvers/buildings_reference/stuck.hpp"

namespace pb::buildings {

inline constexpr int kMaxOrder = 4;  // derivatives the searches read (the Hermite error's f'''')

// Below this |i w - lambda| / w a sinusoid's response is the secular form R E: there the
// particular solution and the free term would each be over 1 / kNearResonance times the
// motion they leave between them.
inline constexpr double kNearResonance = 0.005;

class Motion {
 public:
  // Storage for a scene of n_floors floors and n_contacts contacts.
  void reserve(int n_floors, int n_contacts);

  // The motion from the state (u, v: floor displacements and velocities; g: every contact's
  // gap, read for the open ones) at t0 on the load's piece, valid until horizon.
  void build(const BuildingModel& md, const Reduced& r, const Modal& mo, const double* u, const double* v,
             const double* g, const LoadPiece& piece, double t0, double horizon);

  // The quantities: floors, storey drifts (the storey below each floor), then contacts (an
  // open contact's gap, a stuck one's force).
  int floor(int i) const { return i; }
  int drift(int i) const { return n_floors_ + i; }
  int contact(int j) const { return 2 * n_floors_ + j; }
  int quantities() const { return n_q_; }

  // out[d] = f^(d)(t), d < nd <= kMaxOrder + 1.
  void eval(int q, double t, double* out, int nd);
  // b[0]: |f - mean(q)| over [t, horizon]; b[d], d = 1..kMaxOrder: max |f^(d)| there.
  void bounds(int q, double t, double* b);
  double mean(int q) const;
  // A bound of |f - H| over [t, t + h], H the cubic Hermite interpolant of f on it: mode by
  // mode the smaller of the fourth derivative's charge |a| |lambda|^4 h^4 / 384 and
  // |f_k| + |H_k| <= |a| (2 + 8/27 |lambda| h) (the Hermite basis: h00 + h01 = 1,
  // |h10|, |h11| <= 4/27), times the mode's decay; the near-resonant terms by the former. A fast
  // mode of small amplitude then costs its amplitude, not its frequency: the windows of the
  // searches span it. Never above bounds()' b[4] h^4 / 384.
  double hermite_error(int q, double t, double h);
  double f0(int q) const { return f0_[static_cast<std::size_t>(q)]; }
  double rate0(int q) const { return rate0_[static_cast<std::size_t>(q)]; }  // f'(t0)
  double t0() const { return t0_; }
  double horizon() const { return horizon_; }
  // The largest rate of the motion: its modes' |lambda| and the load's frequencies.
  double fastest() const { return fastest_; }

  // For a quadrature that steps its nodes by products of exponentials instead of evaluating
  // them anew: exp(lambda_k s) for each mode and exp(i w_j s) for each sinusoid (modes() and
  // sines() of them), and every floor's velocity at t = t0 + s from those of s.
  int modes() const { return n_k_; }
  int sines() const { return n_j_; }
  void exp_factors(double s, cplx* modes, cplx* sines) const;
  void floor_velocities(double t, const cplx* modes, const cplx* sines, double* v);

 private:
  struct Resonant {
    int mode = 0, sine = 0;
    cplx a;                                   // +- i w_j
    double bound = 0.0;                       // of |E| over [t0, horizon]
    std::array<cplx, kMaxOrder + 1> a_pow{};  // a^d
    std::array<cplx, kMaxOrder + 1> s_sum{};  // S_d = sum_{j<d} a^j lambda^(d-1-j)
    cplx coef;                                // R: the modal coordinate's term
  };

  // build()'s steps.
  void set_powers(std::size_t m, cplx x);
  void take_load(const LoadPiece& piece);
  void solve_mode(const Reduced& r, const Modal& mo, int k);
  void fill_rows(const BuildingModel& md, const Reduced& r, const Modal& mo);
  bool state_value(const BuildingModel& md, const Reduced& r, int q, const double* u, const double* v, const double* g,
                   double& value, double& rate) const;
  void fill_terms(const BuildingModel& md, const Reduced& r, int q, const double* u, const double* v, const double* g);
  void fill_bounds(int q, double lin, double span);
  void basis(double t, int nd);  // orders 0 .. nd - 1 (at least 2)
  void decays(double t);
  cplx& rho(int q, int k) { return rho_[static_cast<std::size_t>(q * k_max_ + k)]; }
  std::size_t terms() const { return static_cast<std::size_t>(n_k_ + n_j_); }

  int n_floors_ = 0, n_contacts_ = 0, n_q_ = 0, k_max_ = 0;
  std::size_t stride_ = 0;  // of a quantity's terms: k_max_ modes, then kMaxSinusoids sinusoids
  // This segment's modes, sinusoids and near-resonant terms.
  int n_k_ = 0, n_j_ = 0, n_r_ = 0;
  double t0_ = 0.0, horizon_ = 0.0, fastest_ = 0.0;
  // Per term (modes, then sinusoids packed after them): its rate (lambda_k, or i w_j), the
  // table of its powers and their moduli.
  std::vector<cplx> rate_;
  std::vector<std::array<cplx, kMaxOrder + 1>> pow_;
  std::vector<std::array<double, kMaxOrder + 1>> mod_;
  std::vector<double> weight_;  // per mode
  std::vector<Resonant> res_;
  // Per quantity: its modal row (modes only), its terms' coefficients (a_k, then Z_j), the
  // near-resonant coefficients, f0, lin, the mean; and its bounds' parts: constant per order,
  // and per order and mode the coefficient of the mode's decay.
  std::vector<cplx> rho_, coef_, coef_rate_, r_;  // coef_rate_: each coefficient times its rate
  std::vector<double> f0_, lin_, rate0_, mean_, bound_const_, bound_env_, coef_abs_, res4_;
  // Scratch of build(): the load's polynomial and sinusoids (F_j and e^(i w_j t0)), the reduced state.
  double p0_ = 0.0, p1_ = 0.0;
  std::array<cplx, kMaxSinusoids> load_f_{}, load_rot_{};
  std::vector<double> q0_, qd0_, modulus_;
  std::vector<cplx> lin_mode_, h_mode_;
  std::vector<std::array<cplx, 2 * kMaxSinusoids>> x_mode_;  // per mode: X e^(+-i w t0), per sinusoid and sign
  // The basis at one t (every quantity evaluated there shares it): per order, per term,
  // expm1(rate s) for order 0 and rate^d exp(rate s) above.
  double basis_t_ = 0.0;
  bool basis_ok_ = false;
  int basis_nd_ = 0;
  std::array<std::vector<cplx>, kMaxOrder + 1> basis_;
  std::vector<cplx> exp_;  // exp(rate s)
  std::vector<cplx> e_res_;  // E_r(s)
  std::vector<cplx> v_res_;  // floor_velocities' E_r'(s)
  double decay_t_ = 0.0;
  bool decay_ok_ = false;
  std::vector<double> decay_;
};

}  // namespace pb::buildings
