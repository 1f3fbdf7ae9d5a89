#include "cases/system.hpp"

#include <algorithm>
#include <cmath>

#include "cases/physical.hpp"

namespace pb {

namespace {

Body make_body(double m, double w, double xi) { return {m, w, m * w * w, 2.0 * xi * m * w}; }

}  // namespace

System make_system(const Case& c) {
  System s;
  const double w0 = c.pi2 * c.w_p;
  const double m0 = 1.0;  // cancels from Pi1
  const Body b0 = make_body(m0, w0, c.xi);
  switch (c.scene) {
    case Scene::wall:
      s.bodies = {b0};
      s.wall = true;
      s.ref = 0;
      break;
    case Scene::pair:
      s.bodies = {make_body(m0 / c.pi6, w0 / c.pi5, c.xi), b0};
      s.ref = 1;
      break;
    case Scene::row3:
      s.bodies = {make_body(m0 / c.pi6, w0 / c.pi5, c.xi), b0, make_body(m0 / c.pi8, w0 / c.pi7, c.xi)};
      s.ref = 1;
      break;
    case Scene::chain:
      for (int i = 0; i < c.bodies; ++i) s.bodies.push_back(i % 2 == 0 ? b0 : make_body(m0 / c.pi6, w0 / c.pi5, c.xi));
      s.ref = 0;
      break;
  }
  s.delta = c.pi3 * c.a_p / (c.w_p * c.w_p);
  s.eps = c.eps;
  s.xi = c.xi;
  s.a_p = c.a_p;
  s.pulse = make_pulse(c);

  double w_min = s.bodies.front().w, w_max = w_min;
  for (const Body& b : s.bodies) {
    w_min = std::min(w_min, b.w);
    w_max = std::max(w_max, b.w);
  }
  const double two_pi = 2.0 * std::numbers::pi;
  const double t_p = two_pi / c.w_p;
  s.t_end = s.pulse.duration() + c.n_free * two_pi / w_min;
  s.t_min = std::min(t_p, two_pi / w_max);
  s.u_start.assign(s.bodies.size(), 0.0);
  s.v_start.assign(s.bodies.size(), 0.0);
  if (c.scene == Scene::chain) s.v_start[0] = c.kick * c.a_p / c.w_p;
  // Yield displacements: a Pi_y times the length scale (infinity stays infinity).
  const double length = length_unit(c);
  const auto yield_at = [&](double pi_y) { return std::isinf(pi_y) ? pi_y : pi_y * length; };
  if (c.scene == Scene::chain) {
    for (Body& b : s.bodies) b.u_y = yield_at(c.pi_y);
  } else {
    s.bodies[static_cast<std::size_t>(s.ref)].u_y = yield_at(c.pi_y0);
    if (uses_body1(c.scene)) s.bodies[0].u_y = yield_at(c.pi_y1);
    if (uses_body2(c.scene)) s.bodies[2].u_y = yield_at(c.pi_y2);
  }
  s.alpha = c.alpha;
  return s;
}

bool System::yields() const {
  return std::any_of(bodies.begin(), bodies.end(), [](const Body& b) { return b.yields(); });
}

double System::residual(double u, double z) const { return (1.0 - alpha) * (u - z) / length_scale(); }

double System::energy(const double* u, const double* v, const double* z) const {
  double e = 0.0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    e += b.yields() ? b.m * v[i] * v[i] + alpha * b.k * u[i] * u[i] + (1.0 - alpha) * b.k * z[i] * z[i]
                    : b.m * v[i] * v[i] + b.k * u[i] * u[i];
  }
  return 0.5 * e;
}

double System::energy(const double* u, const double* v) const {
  double e = 0.0;
  for (std::size_t i = 0; i < bodies.size(); ++i) e += bodies[i].m * v[i] * v[i] + bodies[i].k * u[i] * u[i];
  return 0.5 * e;
}

double System::energy_scale() const {
  const double speed = a_p / pulse.w;
  double m = 0.0;
  for (const Body& b : bodies) m += b.m;
  const bool at_rest = u_start.size() != bodies.size() || v_start.size() != bodies.size();
  return (at_rest ? 0.0 : energy(u_start.data(), v_start.data())) + 0.5 * m * speed * speed;
}

Case case_of(const System& s) {
  Case c;
  const Body& b0 = s.bodies[static_cast<std::size_t>(s.ref)];
  // Only a chain has its reference body at the left end without a wall.
  c.scene = s.wall ? Scene::wall : s.ref == 0 ? Scene::chain : s.n_bodies() == 2 ? Scene::pair : Scene::row3;
  c.pulse = s.pulse.shape;
  c.cycles = s.pulse.cycles;
  c.mp_gamma = s.pulse.mp_gamma;
  c.mp_nu = s.pulse.mp_nu;
  c.samples = s.pulse.record;
  if (s.pulse.record) c.record = s.pulse.record->source;
  c.directivity = s.pulse.amplitude >= 0.0 ? Directivity::normal : Directivity::reverse;
  c.a_p = s.a_p;
  c.w_p = s.pulse.w;
  c.pi2 = b0.w / s.pulse.w;
  c.pi3 = s.delta / s.length_scale();
  c.eps = s.eps;
  c.xi = s.xi;
  if (c.scene == Scene::pair || c.scene == Scene::row3) {
    const Body& b1 = s.bodies[0];
    c.pi5 = b0.w / b1.w;
    c.pi6 = b0.m / b1.m;
  }
  if (c.scene == Scene::chain) {
    c.bodies = s.n_bodies();
    c.kick = s.v_start.empty() ? 0.0 : s.v_start[0] * s.pulse.w / s.a_p;
    if (s.n_bodies() > 1) {
      c.pi5 = b0.w / s.bodies[1].w;
      c.pi6 = b0.m / s.bodies[1].m;
    }
  }
  if (c.scene == Scene::row3) {
    const Body& b2 = s.bodies[2];
    c.pi7 = b0.w / b2.w;
    c.pi8 = b0.m / b2.m;
  }
  const auto pi_y = [&](const Body& b) { return std::isinf(b.u_y) ? b.u_y : b.u_y / s.length_scale(); };
  if (c.scene == Scene::chain) {
    c.pi_y = pi_y(b0);
  } else {
    c.pi_y0 = pi_y(b0);
    if (c.scene == Scene::pair || c.scene == Scene::row3) c.pi_y1 = pi_y(s.bodies[0]);
    if (c.scene == Scene::row3) c.pi_y2 = pi_y(s.bodies[2]);
  }
  c.alpha = s.alpha;
  double w_min = b0.w;
  for (const Body& b : s.bodies) w_min = std::min(w_min, b.w);
  c.n_free = (s.t_end - s.pulse.duration()) * w_min / (2.0 * std::numbers::pi);
  return c;
}

}  // namespace pb
