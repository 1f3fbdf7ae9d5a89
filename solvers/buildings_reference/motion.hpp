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
  double f0(int q) const { return f0_[static_cast<std::size_t>(q)]; }
  double t0() const { return t0_; }
  double horizon() const { return horizon_; }
  // The largest rate of the motion: its modes' |lambda| and the load's frequencies.
  double fastest() const { return fastest_; }

 private:
  struct Resonant {
    int mode = 0, sine = 0;
    cplx a;                                   // +- i w_j
    double bound = 0.0;                       // of |E| over [t0, horizon]
    std::array<cplx, kMaxOrder + 1> a_pow{};  // a^d
    std::array<cplx, kMaxOrder + 1> s_sum{};  // S_d = sum_{j<d} a^j lambda^(d-1-j)
    cplx coef;                                // R: the modal coordinate's term
  };

  void basis(double t);
  void decays(double t);
  cplx& rho(int q, int k) { return rho_[static_cast<std::size_t>(q * k_max_ + k)]; }

  int n_floors_ = 0, n_contacts_ = 0, n_q_ = 0, k_max_ = 0;
  // This segment's modes, sinusoids and near-resonant terms.
  int n_k_ = 0, n_j_ = 0, n_r_ = 0;
  double t0_ = 0.0, horizon_ = 0.0, fastest_ = 0.0;
  std::vector<cplx> lambda_;
  std::vector<double> weight_;
  std::array<double, kMaxSinusoids> w_{};
  std::vector<Resonant> res_;
  // Per mode: its power table lambda^d and |lambda|^d.
  std::vector<std::array<cplx, kMaxOrder + 1>> lpow_;
  std::vector<std::array<double, kMaxOrder + 1>> lmod_;
  // Per quantity (row-major, q first): modal rows, and the terms of the closed form.
  std::vector<cplx> rho_, a_, z_, r_;
  std::vector<double> f0_, lin_, abs_a_, abs_z_, abs_r_;
  // Scratch of build().
  std::vector<double> q0_, qd0_;
  std::vector<cplx> c0_, lin_mode_, h_mode_;
  std::vector<std::array<cplx, 2 * kMaxSinusoids>> x_mode_;  // per mode: X e^(+-i w t0), per sinusoid and sign
  // The basis at one t (every quantity evaluated there shares it).
  double basis_t_ = 0.0;
  bool basis_ok_ = false;
  std::vector<std::array<cplx, kMaxOrder + 1>> em_;  // per mode: expm1(lambda s), then lambda^d exp(lambda s)
  std::array<std::array<cplx, kMaxOrder + 1>, kMaxSinusoids> ew_{};  // the same for i w_j
  std::vector<cplx> e_res_;                                          // E_r(s)
  double decay_t_ = 0.0;
  bool decay_ok_ = false;
  std::vector<double> decay_;
};

}  // namespace pb::buildings
