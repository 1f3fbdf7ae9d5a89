#include "solvers/buildings_reference/stuck.hpp"

#include <cmath>
#include <numeric>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace pb::buildings {

Reduced make_reduced(const BuildingModel& md, const std::vector<char>& stuck) {
  Reduced r;
  r.stuck = stuck;
  const int nf = md.n_floors;
  const double delta = md.scene.delta;
  r.cluster.assign(static_cast<std::size_t>(nf), -1);
  r.offset = Eigen::VectorXd::Zero(nf);
  // A stuck contact's right floor joins its left floor's cluster, one gap further left:
  // floors are numbered building by building, so the left floor's cluster is known first.
  std::vector<int> joined_to(static_cast<std::size_t>(nf), -1);
  for (std::size_t j = 0; j < md.contacts.size(); ++j)
    if (stuck[j]) joined_to[static_cast<std::size_t>(md.contacts[j].i_right)] = md.contacts[j].i_left;
  for (int i = 0; i < nf; ++i) {
    const int left = joined_to[static_cast<std::size_t>(i)];
    if (left < 0) {
      r.cluster[static_cast<std::size_t>(i)] = r.n++;
    } else {
      r.cluster[static_cast<std::size_t>(i)] = r.cluster[static_cast<std::size_t>(left)];
      r.offset(i) = r.offset(left) - delta;
    }
  }
  const int n = r.n;
  r.floor_mass = md.m;
  r.mass = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < nf; ++i) r.mass(r.cluster[static_cast<std::size_t>(i)]) += md.m(i);
  // K T and C T: floors x clusters (each floor's row summed over the clusters' floors).
  Eigen::MatrixXd kt = Eigen::MatrixXd::Zero(nf, n), ct = Eigen::MatrixXd::Zero(nf, n);
  for (int i = 0; i < nf; ++i)
    for (int k = 0; k < nf; ++k) {
      const int c = r.cluster[static_cast<std::size_t>(k)];
      if (md.K(i, k) != 0.0) kt(i, c) += md.K(i, k);
      if (md.C(i, k) != 0.0) ct(i, c) += md.C(i, k);
    }
  r.K = Eigen::MatrixXd::Zero(n, n);
  r.C = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < nf; ++i) {
    const int c = r.cluster[static_cast<std::size_t>(i)];
    r.K.row(c) += kt.row(i);
    r.C.row(c) += ct.row(i);
  }
  const Eigen::VectorXd ko = md.K * r.offset;
  r.f = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < nf; ++i) r.f(r.cluster[static_cast<std::size_t>(i)]) -= ko(i);
  // Components: buildings joined by stuck contacts, named by their leftmost building.
  std::vector<int> comp(md.scene.buildings.size());
  std::iota(comp.begin(), comp.end(), 0);
  for (std::size_t j = 0; j < md.contacts.size(); ++j)
    if (stuck[j]) {
      const int keep = comp[static_cast<std::size_t>(md.contacts[j].left)];
      const int gone = comp[static_cast<std::size_t>(md.contacts[j].right)];
      for (int& x : comp)
        if (x == gone) x = keep;
    }
  r.component.assign(static_cast<std::size_t>(n), 0);
  for (int i = 0; i < nf; ++i)
    r.component[static_cast<std::size_t>(r.cluster[static_cast<std::size_t>(i)])] =
        comp[static_cast<std::size_t>(md.building_of[static_cast<std::size_t>(i)])];
  // Contact forces (DERIVATION.md §2): within a cluster, the force of the contact right of a
  // floor is what the floors left of it need to follow the cluster,
  //   lambda = -sum over those floors a of e_a,  e_a = m_a q'' + (C u')_a + (K u)_a + m_a a_g,
  // and q'' from the reduced equation, which takes a_g out:
  //   e_a = m_a / m_c (f_c - C_r q' - K_r q)_c + (C T q')_a + (K T q)_a + (K o)_a.
  const auto nc = static_cast<Eigen::Index>(md.contacts.size());
  r.Lq = Eigen::MatrixXd::Zero(nc, n);
  r.Lv = Eigen::MatrixXd::Zero(nc, n);
  r.L0 = Eigen::VectorXd::Zero(nc);
  for (Eigen::Index j = 0; j < nc; ++j) {
    const FloorContact& fc = md.contacts[static_cast<std::size_t>(j)];
    if (!stuck[static_cast<std::size_t>(j)]) continue;
    const int c = r.cluster[static_cast<std::size_t>(fc.i_left)];
    // The cluster's floors at buildings <= fc.left: this level's floors of buildings left of it.
    for (int b = 0; b <= fc.left; ++b) {
      if (fc.floor > md.scene.buildings[static_cast<std::size_t>(b)].floors()) continue;
      const int a = md.global(b, fc.floor);
      if (r.cluster[static_cast<std::size_t>(a)] != c) continue;
      const double share = md.m(a) / r.mass(c);
      r.Lq.row(j) -= kt.row(a) - share * r.K.row(c);
      r.Lv.row(j) -= ct.row(a) - share * r.C.row(c);
      r.L0(j) -= ko(a) + share * r.f(c);
    }
  }
  return r;
}

void Reduced::reduce(const double* u, const double* v, double* q, double* qd) const {
  for (int c = 0; c < n; ++c) q[c] = qd[c] = 0.0;
  for (std::size_t i = 0; i < cluster.size(); ++i) {
    const int c = cluster[i];
    const auto ii = static_cast<Eigen::Index>(i);
    q[c] += floor_mass(ii) * (u[i] - offset(ii));
    qd[c] += floor_mass(ii) * v[i];
  }
  for (int c = 0; c < n; ++c) {
    q[c] /= mass(c);
    qd[c] /= mass(c);
  }
}

namespace {

// One component's modes into the Modal (columns `at` on), from its clusters `cl`.
class ModalBuilder {
 public:
  ModalBuilder(const BuildingModel& md, const Reduced& r, Modal& out) : md_(md), r_(r), out_(out) {}

  void component(const std::vector<int>& cl, int building_alone) {
    const auto n = static_cast<Eigen::Index>(cl.size());
    Eigen::VectorXd sm(n);  // sqrt of the clusters' masses
    for (Eigen::Index a = 0; a < n; ++a) sm(a) = std::sqrt(r_.mass(cl[static_cast<std::size_t>(a)]));
    Eigen::MatrixXd phit(n, n);  // Phi~: orthonormal
    Eigen::VectorXd w(n), xi(n);
    bool classical = true;
    Eigen::MatrixXd d;
    if (building_alone >= 0) {
      // The building's own modes: Phi~ = M^1/2 Phi, and its damping ratio per mode.
      const BuildingModes& bm = md_.modes[static_cast<std::size_t>(building_alone)];
      phit = sm.asDiagonal() * bm.phi;
      w = bm.w;
      xi = bm.xi;
    } else {
      Eigen::MatrixXd kr(n, n), cr(n, n);
      for (Eigen::Index a = 0; a < n; ++a)
        for (Eigen::Index b = 0; b < n; ++b) {
          kr(a, b) = r_.K(cl[static_cast<std::size_t>(a)], cl[static_cast<std::size_t>(b)]) / (sm(a) * sm(b));
          cr(a, b) = r_.C(cl[static_cast<std::size_t>(a)], cl[static_cast<std::size_t>(b)]) / (sm(a) * sm(b));
        }
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(kr);
      phit = es.eigenvectors();
      w = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
      xi.setZero();
      if (!cr.isZero(0.0)) {
        classical = false;
        d = phit.transpose() * cr * phit;
      }
    }
    // Rows of eta = Phi~^T M^1/2 q and of Phi~^T M^-1/2 (a force on the clusters).
    const Eigen::MatrixXd to_eta = phit.transpose() * sm.asDiagonal();
    const Eigen::MatrixXd load = phit.transpose() * sm.cwiseInverse().asDiagonal();
    Eigen::VectorXd fc(n), mr(n);
    for (Eigen::Index a = 0; a < n; ++a) {
      fc(a) = r_.f(cl[static_cast<std::size_t>(a)]);
      mr(a) = r_.mass(cl[static_cast<std::size_t>(a)]);
    }
    const Eigen::VectorXd g_c = load * fc, g_a = -(load * mr);
    // Shapes in q: q = M^-1/2 Phi~ eta.
    const Eigen::MatrixXd from_eta = sm.cwiseInverse().asDiagonal() * phit;
    if (classical) {
      for (Eigen::Index m = 0; m < n; ++m) classical_mode(cl, m, w(m), xi(m), to_eta, from_eta, g_c(m), g_a(m));
    } else {
      general(cl, w, d, to_eta, from_eta, g_c, g_a);
    }
  }

 private:
  // Mode m of a classically damped component: the 2x2 block [[0, w], [-w, -2 xi w]] of
  // z_m = (w eta_m, eta_m'), eigenvector (w, lambda) for each root lambda.
  void classical_mode(const std::vector<int>& cl, Eigen::Index m, double w, double xi, const Eigen::MatrixXd& to_eta,
                      const Eigen::MatrixXd& from_eta, double gc, double ga) {
    const double gap = std::abs(1.0 - xi * xi);
    if (!(gap > 1.0 / (kMaxModalCondition * kMaxModalCondition))) {
      std::ostringstream msg;
      msg << "a mode of frequency " << w << " rad/s is critically damped (xi = " << xi
          << "): its two roots coincide, which the modal closed form cannot take";
      fail(msg.str());
      return;
    }
    if (xi < 1.0) {
      // lambda = -sigma + i wd; c = (eta' - conj(lambda) eta) / (2 i wd), and z_m = 2 Re(c (w, lambda)).
      const double sigma = xi * w, wd = w * std::sqrt((1.0 - xi) * (1.0 + xi));
      const cplx lambda(-sigma, wd), den(0.0, 2.0 * wd);
      add(cl, lambda, 2.0, from_eta.col(m), -std::conj(lambda) / den, 1.0 / den, to_eta.row(m), gc / den, ga / den);
    } else {
      // Two real roots, the slow one without cancellation (lambda1 lambda2 = w^2);
      // c1 = (eta' - lambda2 eta) / (lambda1 - lambda2), c2 = (lambda1 eta - eta') / (lambda1 - lambda2).
      const double root = std::sqrt((xi - 1.0) * (xi + 1.0));
      const double fast = -w * (xi + root), slow = w * w / fast, den = slow - fast;
      add(cl, cplx(slow), 1.0, from_eta.col(m), cplx(-fast / den), cplx(1.0 / den), to_eta.row(m), gc / den,
          ga / den);
      add(cl, cplx(fast), 1.0, from_eta.col(m), cplx(slow / den), cplx(-1.0 / den), to_eta.row(m), -gc / den,
          -ga / den);
    }
  }

  // A mode: its root, weight, shape in q (real here), and c = cq eta_m + cv eta_m' where to_eta
  // gives eta_m, and its load terms.
  void add(const std::vector<int>& cl, cplx lambda, double weight, const Eigen::VectorXd& shape, cplx cq, cplx cv,
           const Eigen::RowVectorXd& to_eta, cplx gamma, cplx alpha) {
    const Eigen::Index k = out_.n++;
    out_.lambda(k) = lambda;
    out_.weight(k) = weight;
    for (std::size_t a = 0; a < cl.size(); ++a) {
      const auto c = static_cast<Eigen::Index>(cl[a]);
      out_.shape(c, k) = shape(static_cast<Eigen::Index>(a));
      out_.in_q(k, c) = cq * to_eta(static_cast<Eigen::Index>(a));
      out_.in_v(k, c) = cv * to_eta(static_cast<Eigen::Index>(a));
    }
    out_.gamma(k) = gamma;
    out_.alpha(k) = alpha;
  }

  void general(const std::vector<int>& cl, const Eigen::VectorXd& w, const Eigen::MatrixXd& d,
               const Eigen::MatrixXd& to_eta, const Eigen::MatrixXd& from_eta, const Eigen::VectorXd& g_c,
               const Eigen::VectorXd& g_a) {
    const Eigen::Index n = w.size();
    Eigen::MatrixXd first_order = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    first_order.topRightCorner(n, n) = w.asDiagonal();
    first_order.bottomLeftCorner(n, n) = -w.asDiagonal().toDenseMatrix();
    first_order.bottomRightCorner(n, n) = -d;
    const Eigen::EigenSolver<Eigen::MatrixXd> es(first_order, true);
    if (es.info() != Eigen::Success) {
      fail("the eigen-decomposition of the stuck buildings' motion did not converge");
      return;
    }
    const Eigen::VectorXcd lambda = es.eigenvalues();
    const Eigen::MatrixXcd v = es.eigenvectors();
    const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(v);
    const Eigen::MatrixXcd vinv = lu.inverse();
    const double cond = v.cwiseAbs().colwise().sum().maxCoeff() * vinv.cwiseAbs().colwise().sum().maxCoeff();
    if (!(cond < kMaxModalCondition)) {
      std::ostringstream msg;
      msg << "the stuck buildings' modes are nearly defective (eigenvector condition " << cond
          << "): a mode near critical damping, which the modal closed form cannot take";
      fail(msg.str());
      return;
    }
    // q = M^-1/2 Phi~ Omega^-1 z_top; c_k = vinv.row(k) z with z = (Omega eta, eta').
    const Eigen::MatrixXd in_top = w.asDiagonal() * to_eta;  // z_top from q
    for (Eigen::Index k = 0; k < 2 * n; ++k) {
      if (lambda(k).imag() < 0.0) continue;  // the conjugate of the mode before it
      const double weight = lambda(k).imag() > 0.0 ? 2.0 : 1.0;
      const Eigen::Index m = out_.n++;
      out_.lambda(m) = lambda(k);
      out_.weight(m) = weight;
      const Eigen::VectorXcd shape = from_eta * (w.cwiseInverse().asDiagonal() * v.col(k).head(n));
      const Eigen::RowVectorXcd cq = vinv.row(k).head(n) * in_top;
      const Eigen::RowVectorXcd cv = vinv.row(k).tail(n) * to_eta;
      for (std::size_t a = 0; a < cl.size(); ++a) {
        const auto c = static_cast<Eigen::Index>(cl[a]);
        const auto ai = static_cast<Eigen::Index>(a);
        out_.shape(c, m) = shape(ai);
        out_.in_q(m, c) = cq(ai);
        out_.in_v(m, c) = cv(ai);
      }
      out_.gamma(m) = vinv.row(k).tail(n) * g_c;
      out_.alpha(m) = vinv.row(k).tail(n) * g_a;
    }
  }

  void fail(std::string why) {
    if (out_.ok) out_.why = std::move(why);
    out_.ok = false;
  }

  const BuildingModel& md_;
  const Reduced& r_;
  Modal& out_;
};

}  // namespace

Modal make_modal(const BuildingModel& md, const Reduced& r) {
  Modal out;
  // At most two roots per cluster.
  out.lambda.resize(2 * r.n);
  out.weight.resize(2 * r.n);
  out.shape = Eigen::MatrixXcd::Zero(r.n, 2 * r.n);
  out.in_q = Eigen::MatrixXcd::Zero(2 * r.n, r.n);
  out.in_v = Eigen::MatrixXcd::Zero(2 * r.n, r.n);
  out.gamma.resize(2 * r.n);
  out.alpha.resize(2 * r.n);
  ModalBuilder builder(md, r, out);
  const int nb = static_cast<int>(md.scene.buildings.size());
  for (int comp = 0; comp < nb; ++comp) {
    std::vector<int> cl;
    for (int c = 0; c < r.n; ++c)
      if (r.component[static_cast<std::size_t>(c)] == comp) cl.push_back(c);
    if (cl.empty()) continue;
    // A building alone keeps its own modes: no other building is in its component.
    int alone = comp;
    for (int b = 0; b < nb; ++b)
      if (b != comp && r.component[static_cast<std::size_t>(r.cluster[static_cast<std::size_t>(md.global(b, 1))])] == comp)
        alone = -1;
    builder.component(cl, alone);
  }
  out.lambda.conservativeResize(out.n);
  out.weight.conservativeResize(out.n);
  out.shape.conservativeResize(Eigen::NoChange, out.n);
  out.in_q.conservativeResize(out.n, Eigen::NoChange);
  out.in_v.conservativeResize(out.n, Eigen::NoChange);
  out.gamma.conservativeResize(out.n);
  out.alpha.conservativeResize(out.n);
  return out;
}

}  // namespace pb::buildings
