#pragma once
// The buildings' motion for one set of stuck contacts (DERIVATION.md §1, §2).
//
// Floors joined by stuck contacts (one level, neighbouring buildings) form a cluster that
// moves as one, each floor at its offset (u = q - delta per contact to its left within the
// cluster): u = T q + o, T the floor-cluster incidence (a basis of the null space of the
// stuck contacts' W columns, in 0s and 1s, so that it adds no round-off). The reduced system
//
//   M_r q'' + C_r q' + K_r q = f_c - m_r a_g(t),   M_r = T^T M T, C_r = T^T C T, K_r = T^T K T,
//   f_c = -T^T K o,  m_r = T^T M 1 (the clusters' masses)
//
// is linear; the contact forces drop out (W_S^T T = 0). Reduced: the matrices and the
// contact forces as functions of (q, q'), cheap, for the acceleration LCP's candidates.
// Modal: the eigen-decomposition of its first-order form, for the closed form between events.
//
// Buildings joined by stuck contacts form a component. A component of one building alone is
// classically damped (Rayleigh and modal damping both), and takes the building's own modes:
// the no-contact motion is modal superposition. A larger one generally is not (the
// buildings' damping rules differ), and takes the complex modes of
//
//   z' = A z + (0, g(t)),  A = [[0, Omega], [-Omega, -D]],  z = (Omega eta, eta'),
//   eta = Phi~^T M_r^1/2 q,  K~ = M_r^-1/2 K_r M_r^-1/2 = Phi~ Omega^2 Phi~^T,  D = Phi~^T M_r^-1/2 C_r M_r^-1/2 Phi~:
//
// |z|^2 is twice the energy, so A is a skew matrix plus the damping and its eigenvectors
// are well conditioned (a normal matrix without damping).

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cases/buildings.hpp"

namespace pb::buildings {

using cplx = std::complex<double>;

struct Reduced {
  std::vector<char> stuck;   // per contact
  int n = 0;                 // clusters
  std::vector<int> cluster;  // per floor
  Eigen::VectorXd offset;    // per floor: u_i = q_cluster(i) + offset_i
  Eigen::VectorXd mass;      // per cluster
  Eigen::VectorXd floor_mass;
  Eigen::MatrixXd K, C;      // reduced, n x n
  Eigen::VectorXd f;         // f_c = -T^T K o
  // The force of each contact: lambda = Lq q + Lv q' + L0 for a stuck one (0 for an open one).
  Eigen::MatrixXd Lq, Lv;  // contacts x n
  Eigen::VectorXd L0;
  std::vector<int> component;  // per cluster: the buildings it joins, numbered by their leftmost
  // The reduced state of a floor state: each cluster's mass-weighted u - o and v.
  void reduce(const double* u, const double* v, double* q, double* qd) const;
};

Reduced make_reduced(const BuildingModel& md, const std::vector<char>& stuck);

// The complex modes of a Reduced system. Each real solution is sum over modes k of
// weight_k Re(c_k(t) shape_k), weight 2 for a mode of a conjugate pair (only the one with
// Im lambda > 0 is kept) and 1 for a real one (an overdamped mode): c_k' = lambda_k c_k +
// gamma_k + alpha_k a_g(t), and c_k = in_q.row(k) q + in_v.row(k) q' from a reduced state.
struct Modal {
  bool ok = true;
  std::string why;  // when not ok: near-defective modes (critical damping)
  int n = 0;        // modes kept
  Eigen::VectorXcd lambda;
  Eigen::VectorXd weight;
  Eigen::MatrixXcd shape;       // clusters x modes: q of each mode
  Eigen::MatrixXcd in_q, in_v;  // modes x clusters
  Eigen::VectorXcd gamma, alpha;
};

Modal make_modal(const BuildingModel& md, const Reduced& r);

// Above this condition number of a component's eigenvector matrix its modes are taken as
// defective (a mode at critical damping): the closed form would lose more than 1e-8.
inline constexpr double kMaxModalCondition = 1e8;

}  // namespace pb::buildings
