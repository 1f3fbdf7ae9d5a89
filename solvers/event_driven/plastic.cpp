#include "solvers/event_driven/plastic.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "solvers/event_driven/search.hpp"

namespace pb::event_driven {

namespace {

// Gauss-Legendre, 8 points on [-1, 1]: exact for polynomials of degree 15. Its error on a
// panel of length h is h^17 (8!)^4 / (17 (16!)^3) max|f^(16)|, 1.7e-23 h^17 max|f^(16)|. The
// integrands are products of two motions of frequency w <= 2 pi / T_min (or decay rates
// below that), so |f^(16)| <= (2 w)^16 |f|, and on panels of T_min / 8 (2 w h <= pi / 2) the
// error is below 3e-20 of the panel's scale.
constexpr std::array<double, 4> kNodes = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                          0.9602898564975363};
constexpr std::array<double, 4> kWeights = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                            0.1012285362903763};

}  // namespace

void Plasticity::start(const System& s, State& st, Frame& fr) {
  on_ = s.yields();
  hysteretic_ = hysteretic_ref_ = input_ = damped_ = 0.0;
  if (!on_) {
    st.branch.clear();
    st.e.clear();
    fr.yield.clear();
    return;
  }
  const auto n = ix(s.n_bodies());
  st.branch.assign(n, 0);
  st.e.assign(n, 0.0);
  onset_.assign(n, 0.0);
  z_.assign(n, 0.0);
  fr.yield.resize(2 * n);
}

YieldEvent Plasticity::next(const System& s, const State& st, const Frame& fr, double b, double floor, double settle,
                            double noise_u, double noise_v, Deadline& deadline) const {
  YieldEvent first{std::numeric_limits<double>::quiet_NaN()};
  double earliest = b;
  for (int i = 0; i < s.n_bodies(); ++i) {
    if (!s.bodies[ix(i)].yields()) continue;
    const bool elastic = st.branch[ix(i)] == 0;
    for (int side = 0; side < (elastic ? 2 : 1); ++side) {
      const double r =
          first_root(fr.yield[ix(2 * i + side)], st.t, earliest, floor, settle, elastic ? noise_u : noise_v, deadline);
      if (!std::isnan(r) && r < earliest) {
        earliest = r;
        first = {r, i, side};
      }
    }
  }
  return first;
}

void Plasticity::close_phase(const System& s, const State& st, int i) {
  const Body& b = s.bodies[ix(i)];
  const double w = (1.0 - s.alpha) * b.k * b.u_y * std::abs(st.u[ix(i)] - onset_[ix(i)]);
  hysteretic_ += w;
  if (i == s.ref) hysteretic_ref_ += w;
}

void Plasticity::change(const System& s, State& st, const YieldEvent& event) {
  const auto i = ix(event.body);
  if (st.branch[i] == 0) {
    st.branch[i] = event.side == 0 ? 1 : -1;
    onset_[i] = st.u[i];
  } else {
    close_phase(s, st, event.body);
    st.e[i] = st.u[i] - st.branch[i] * s.bodies[i].u_y;
    st.branch[i] = 0;
  }
}

void Plasticity::settle(const System& s, State& st, double tol_u, double tol_v) {
  for (int i = 0; i < s.n_bodies(); ++i) {
    const Body& b = s.bodies[ix(i)];
    if (!b.yields()) continue;
    const double v = st.v[ix(i)];
    const int branch = st.branch[ix(i)];
    if (branch == 0) {
      const double z = st.u[ix(i)] - st.e[ix(i)];
      const int side = z > 0.0 ? 1 : -1;
      if (side * z >= b.u_y - tol_u && side * v > tol_v) {
        st.branch[ix(i)] = static_cast<signed char>(side);
        onset_[ix(i)] = st.u[ix(i)];
      }
    } else if (branch * v < -tol_v) {
      close_phase(s, st, i);
      st.e[ix(i)] = st.u[ix(i)] - branch * b.u_y;
      st.branch[ix(i)] = 0;
    }
  }
}

void Plasticity::integrate(const System& s, const Frame& fr, double a, double b) {
  if (!(b > a)) return;
  const double panel_max = s.t_min / 8.0;
  const auto panels = static_cast<long>(std::ceil((b - a) / panel_max));
  const double h = (b - a) / static_cast<double>(panels);
  double work = 0.0, damping = 0.0;
  for (long p = 0; p < panels; ++p) {
    const double mid = a + (static_cast<double>(p) + 0.5) * h;
    for (std::size_t q = 0; q < 2 * kNodes.size(); ++q) {
      const double x = q < kNodes.size() ? -kNodes[q] : kNodes[q - kNodes.size()];
      const double weight = 0.5 * h * kWeights[q % kNodes.size()];
      const double t = mid + 0.5 * h * x;
      double momentum = 0.0, power = 0.0;
      for (int i = 0; i < s.n_bodies(); ++i) {
        double uv[2];
        fr.body[ix(i)].eval(t, uv, 2);
        const Body& body = s.bodies[ix(i)];
        momentum += body.m * uv[1];
        power += body.c * uv[1] * uv[1];
      }
      work -= weight * s.pulse.accel(t) * momentum;
      damping += weight * power;
    }
  }
  input_ += work;
  damped_ += damping;
}

double Plasticity::energy(const System& s, const State& st, const double* u, const double* v) {
  for (int i = 0; i < s.n_bodies(); ++i) {
    const int branch = st.branch[ix(i)];
    z_[ix(i)] = branch == 0 ? u[i] - st.e[ix(i)] : branch * s.bodies[ix(i)].u_y;
  }
  return s.energy(u, v, z_.data());
}

void Plasticity::finish(const System& s, const State& st, double impact_losses, Result& r) {
  for (int i = 0; i < s.n_bodies(); ++i)
    if (s.bodies[ix(i)].yields() && st.branch[ix(i)] != 0) {
      close_phase(s, st, i);  // a phase still going at t_end, counted to there
      onset_[ix(i)] = st.u[ix(i)];
    }
  double kinetic = 0.0;
  for (int i = 0; i < s.n_bodies(); ++i) kinetic += 0.5 * s.bodies[ix(i)].m * st.v[ix(i)] * st.v[ix(i)];
  r.energies.input = input_;
  r.energies.kinetic = kinetic;
  r.energies.elastic = energy(s, st, st.u.data(), st.v.data()) - kinetic;
  r.energies.damped = damped_;
  r.energies.hysteretic = hysteretic_;
  r.energies.impacts = impact_losses;
  r.residual = s.residual(st.u[ix(s.ref)], hysteretic_z(s, st, s.ref));
  r.hysteretic = hysteretic_ref_ / input_;
}

}  // namespace pb::event_driven
