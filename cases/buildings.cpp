#include "cases/buildings.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <Eigen/SVD>

namespace pb {

namespace {

bool positive_finite(double x) { return std::isfinite(x) && x > 0.0; }

std::string building_problem(const Building& b, std::size_t index) {
  std::ostringstream msg;
  msg << "buildings[" << index << "]: ";
  if (b.masses.empty()) return msg.str() + "has no floors";
  if (b.masses.size() != b.stiffnesses.size()) {
    msg << b.masses.size() << " masses and " << b.stiffnesses.size() << " stiffnesses (one per storey)";
    return msg.str();
  }
  if (b.masses.size() > static_cast<std::size_t>(kMaxBuildingFloors)) {
    msg << b.masses.size() << " floors, more than " << kMaxBuildingFloors;
    return msg.str();
  }
  for (std::size_t i = 0; i < b.masses.size(); ++i) {
    if (!positive_finite(b.masses[i])) {
      msg << "the mass of floor " << i + 1 << " must be finite and > 0";
      return msg.str();
    }
    if (!positive_finite(b.stiffnesses[i])) {
      msg << "the stiffness of storey " << i + 1 << " must be finite and > 0";
      return msg.str();
    }
  }
  return {};
}

// The scales of a scene's pulse where the scene gives none.
double pulse_a_p(const Pulse& p) {
  if (p.record) return std::abs(p.amplitude) * p.record->peak;
  return std::abs(p.amplitude);
}

}  // namespace

std::string validate(const BuildingScene& s) {
  if (s.buildings.size() < 2 || s.buildings.size() > 3) {
    std::ostringstream msg;
    msg << "buildings: " << s.buildings.size() << " given, the scene has two or three";
    return msg.str();
  }
  for (std::size_t b = 0; b < s.buildings.size(); ++b)
    if (std::string why = building_problem(s.buildings[b], b); !why.empty()) return why;
  if (!(s.xi >= 0.0 && s.xi < 1.0)) return "xi: must be in [0, 1)";
  if (!(std::isfinite(s.delta) && s.delta >= 0.0)) return "gap: must be finite and >= 0";
  if (!(s.eps >= 0.0 && s.eps <= 1.0)) return "eps: must be in [0, 1]";
  for (std::size_t a = 0; a < s.contact_floors.size(); ++a) {
    const int f = s.contact_floors[a];
    if (std::count(s.contact_floors.begin(), s.contact_floors.end(), f) > 1) {
      std::ostringstream msg;
      msg << "contact_floors: floor " << f << " named twice";
      return msg.str();
    }
    for (std::size_t b = 0; b + 1 < s.buildings.size(); ++b) {
      const int top = std::min(s.buildings[b].floors(), s.buildings[b + 1].floors());
      if (f < 1 || f > top) {
        std::ostringstream msg;
        msg << "contact_floors: floor " << f << " is not a floor both buildings " << b << " and " << b + 1
            << " have (1.." << top << ")";
        return msg.str();
      }
    }
  }
  if (!(std::isfinite(s.t_end) && s.t_end >= 0.0)) return "t_end: must be finite and > 0 (0: the default)";
  if (!positive_finite(s.n_free)) return "n_free: must be finite and > 0";
  if (!(std::isfinite(s.a_p) && s.a_p >= 0.0)) return "a_p: must be finite and > 0 (0: the pulse's)";
  if (!(std::isfinite(s.w_p) && s.w_p >= 0.0)) return "w_p: must be finite and > 0 (0: the pulse's)";
  if (!positive_finite(s.w_p > 0.0 ? s.w_p : s.pulse.w)) return "w_p: the pulse has no circular frequency > 0";
  if (!positive_finite(s.a_p > 0.0 ? s.a_p : pulse_a_p(s.pulse)))
    return "a_p: the pulse has no amplitude > 0 to scale tolerances with";
  if (!(s.pulse.duration() >= 0.0 && std::isfinite(s.pulse.duration()))) return "pulse: its duration is not finite";
  return {};
}

BuildingModes building_modes(const Building& b) {
  const int n = b.floors();
  // G = diag(sqrt k) B M^-1/2: row i is storey i's drift u_i - u_{i-1}, scaled; K~ = G^T G.
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    const double sk = std::sqrt(b.stiffnesses[static_cast<std::size_t>(i)]);
    g(i, i) = sk / std::sqrt(b.masses[static_cast<std::size_t>(i)]);
    if (i > 0) g(i, i - 1) = -sk / std::sqrt(b.masses[static_cast<std::size_t>(i - 1)]);
  }
  // Two-sided Jacobi without a QR step first: on this bidiagonal G it keeps the small
  // singular values' relative accuracy.
  const Eigen::JacobiSVD<Eigen::MatrixXd, Eigen::NoQRPreconditioner> svd(g, Eigen::ComputeFullV);
  BuildingModes modes;
  modes.w.resize(n);
  modes.phi.resize(n, n);
  for (int r = 0; r < n; ++r) {
    const int from = n - 1 - r;  // singular values come in descending order
    modes.w(r) = svd.singularValues()(from);
    Eigen::VectorXd v = svd.matrixV().col(from);
    // A sign of our own: the top floor moves +x (a deterministic mode shape).
    if (v(n - 1) < 0.0) v = -v;
    for (int i = 0; i < n; ++i) modes.phi(i, r) = v(i) / std::sqrt(b.masses[static_cast<std::size_t>(i)]);
  }
  modes.xi = Eigen::VectorXd::Zero(n);
  return modes;
}

void rayleigh_coefficients(double xi, double w1, double w2, double& a0, double& a1) {
  a0 = 2.0 * xi * w1 * w2 / (w1 + w2);
  a1 = 2.0 * xi / (w1 + w2);
}

BuildingModel assemble(const BuildingScene& scene) {
  BuildingModel md;
  md.scene = scene;
  const auto nb = scene.buildings.size();
  for (const Building& b : scene.buildings) {
    md.first.push_back(md.n_floors);
    md.n_floors += b.floors();
  }
  const int n = md.n_floors;
  md.m.resize(n);
  md.k.resize(n);
  md.K = Eigen::MatrixXd::Zero(n, n);
  md.C = Eigen::MatrixXd::Zero(n, n);
  md.building_of.resize(static_cast<std::size_t>(n));
  md.a_p = scene.a_p > 0.0 ? scene.a_p : pulse_a_p(scene.pulse);
  md.w_p = scene.w_p > 0.0 ? scene.w_p : scene.pulse.w;
  double w_max = md.w_p, w_first = std::numeric_limits<double>::infinity();
  for (std::size_t bi = 0; bi < nb; ++bi) {
    const Building& b = scene.buildings[bi];
    const int f0 = md.first[bi], nf = b.floors();
    for (int i = 0; i < nf; ++i) {
      const int g = f0 + i;
      md.building_of[static_cast<std::size_t>(g)] = static_cast<int>(bi);
      md.m(g) = b.masses[static_cast<std::size_t>(i)];
      const double k = b.stiffnesses[static_cast<std::size_t>(i)];
      md.k(g) = k;
      md.K(g, g) += k;
      if (i > 0) {
        md.K(g - 1, g - 1) += k;
        md.K(g, g - 1) = md.K(g - 1, g) = -k;
      }
    }
    BuildingModes modes = building_modes(b);
    const auto block = Eigen::seqN(f0, nf);
    if (scene.damping == BuildingDamping::rayleigh) {
      const double w1 = modes.w(0), w2 = nf > 1 ? modes.w(1) : modes.w(0);
      double a0, a1;
      rayleigh_coefficients(scene.xi, w1, w2, a0, a1);
      md.C(block, block) = a1 * md.K(block, block);
      md.C(block, block).diagonal() += a0 * md.m.segment(f0, nf);
      modes.xi = (a0 / (2.0 * modes.w.array()) + a1 * modes.w.array() / 2.0).matrix();
    } else {
      const Eigen::MatrixXd mphi = md.m.segment(f0, nf).asDiagonal() * modes.phi;
      const Eigen::VectorXd c = 2.0 * scene.xi * modes.w;
      md.C(block, block) = mphi * c.asDiagonal() * mphi.transpose();
      modes.xi.setConstant(scene.xi);
    }
    w_max = std::max(w_max, modes.w(nf - 1));
    w_first = std::min(w_first, modes.w(0));
    md.modes.push_back(std::move(modes));
  }
  if (!scene.no_contact) {
    for (std::size_t bi = 0; bi + 1 < nb; ++bi) {
      const int top = std::min(scene.buildings[bi].floors(), scene.buildings[bi + 1].floors());
      for (int f = 1; f <= top; ++f) {
        const auto& named = scene.contact_floors;
        if (!named.empty() && std::find(named.begin(), named.end(), f) == named.end()) continue;
        const int l = static_cast<int>(bi);
        md.contacts.push_back({l, l + 1, f, md.global(l, f), md.global(l + 1, f)});
      }
    }
  }
  const double two_pi = 2.0 * std::numbers::pi;
  md.t_end = scene.t_end > 0.0 ? scene.t_end : scene.pulse.duration() + scene.n_free * two_pi / w_first;
  md.t_min = two_pi / w_max;  // w_max: the pulse's w_p and every building's highest mode
  return md;
}

double BuildingModel::energy(const double* u, const double* v) const {
  double e = 0.0;
  for (int i = 0; i < n_floors; ++i) {
    e += m(i) * v[i] * v[i];
    // The storey below floor i: its drift (the ground below floor 1 of each building).
    const bool bottom = i == first[static_cast<std::size_t>(building_of[static_cast<std::size_t>(i)])];
    const double drift = bottom ? u[i] : u[i] - u[i - 1];
    e += k(i) * drift * drift;
  }
  return 0.5 * e;
}

double BuildingModel::energy_scale() const {
  const double v = speed_scale();
  return 0.5 * m.sum() * v * v;
}

Building uniform_building(int floors, double mass, double w1) {
  const double s = 2.0 * std::sin(std::numbers::pi / (2.0 * (2.0 * floors + 1.0)));
  const double root = w1 / s;  // sqrt(k / m)
  Building b;
  b.masses.assign(static_cast<std::size_t>(floors), mass);
  b.stiffnesses.assign(static_cast<std::size_t>(floors), mass * root * root);
  return b;
}

BuildingScene uniform_pair(int floors_left, int floors_right, double pi2, double pi3, double pi4, double pi5,
                           double pi6, const Pulse& pulse, double a_p, double w_p) {
  BuildingScene s;
  const double w_left = pi2 * w_p;
  const double m_left = 1.0;
  // pi6 = n_left m_left / (n_right m_right)
  const double m_right = floors_left * m_left / (pi6 * floors_right);
  s.buildings = {uniform_building(floors_left, m_left, w_left), uniform_building(floors_right, m_right, w_left / pi5)};
  s.delta = pi3 * a_p / (w_p * w_p);
  s.eps = pi4;
  s.pulse = pulse;
  s.a_p = a_p;
  s.w_p = w_p;
  return s;
}

double contact_element_stiffness(const BuildingModel& model, bool hertz, double K) {
  const int f0 = model.first.front(), floors = model.scene.buildings.front().floors();
  const double w1 = model.modes.front().w(0);
  const double linear = K * model.m.segment(f0, floors).sum() * w1 * w1;
  if (!hertz) return linear;
  const Pulse& pulse = model.scene.pulse;
  return linear / std::sqrt(pulse.record ? pulse.record->length_scale() : model.length_scale());
}

}  // namespace pb
