#include "cases/system.hpp"

#include <algorithm>

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
  }
  s.delta = c.pi3 * c.a_p / (c.w_p * c.w_p);
  s.eps = c.eps;
  s.xi = c.xi;
  s.a_p = c.a_p;
  s.pulse = {c.pulse, c.directivity == Directivity::normal ? c.a_p : -c.a_p, c.w_p};

  double w_min = s.bodies.front().w, w_max = w_min;
  for (const Body& b : s.bodies) {
    w_min = std::min(w_min, b.w);
    w_max = std::max(w_max, b.w);
  }
  const double two_pi = 2.0 * std::numbers::pi;
  const double t_p = s.pulse.duration();
  s.t_end = t_p + c.n_free * two_pi / w_min;
  s.t_min = std::min(t_p, two_pi / w_max);
  return s;
}

Case case_of(const System& s) {
  Case c;
  const Body& b0 = s.bodies[static_cast<std::size_t>(s.ref)];
  c.scene = s.wall ? Scene::wall : s.n_bodies() == 2 ? Scene::pair : Scene::row3;
  c.pulse = s.pulse.shape;
  c.directivity = s.pulse.amplitude >= 0.0 ? Directivity::normal : Directivity::reverse;
  c.a_p = s.a_p;
  c.w_p = s.pulse.w;
  c.pi2 = b0.w / s.pulse.w;
  c.pi3 = s.delta / s.length_scale();
  c.eps = s.eps;
  c.xi = s.xi;
  if (!s.wall) {
    const Body& b1 = s.bodies[0];
    c.pi5 = b0.w / b1.w;
    c.pi6 = b0.m / b1.m;
  }
  if (s.n_bodies() == 3) {
    const Body& b2 = s.bodies[2];
    c.pi7 = b0.w / b2.w;
    c.pi8 = b0.m / b2.m;
  }
  double w_min = b0.w;
  for (const Body& b : s.bodies) w_min = std::min(w_min, b.w);
  c.n_free = (s.t_end - s.pulse.duration()) * w_min / (2.0 * std::numbers::pi);
  return c;
}

}  // namespace pb
