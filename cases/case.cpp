#include "cases/case.hpp"

#include <cmath>
#include <string>

namespace pb {

std::string_view name(Scene s) {
  switch (s) {
    case Scene::wall: return "wall";
    case Scene::pair: return "pair";
    case Scene::row3: return "row3";
    case Scene::chain: return "chain";
  }
  return "?";
}

std::string_view name(PulseShape p) { return p == PulseShape::sine ? "sine" : "cosine"; }

std::string_view name(Directivity d) { return d == Directivity::normal ? "normal" : "reverse"; }

std::optional<Scene> parse_scene(std::string_view s) {
  for (Scene v : {Scene::wall, Scene::pair, Scene::row3, Scene::chain})
    if (name(v) == s) return v;
  return std::nullopt;
}

std::optional<PulseShape> parse_pulse(std::string_view s) {
  for (PulseShape v : {PulseShape::sine, PulseShape::cosine})
    if (name(v) == s) return v;
  return std::nullopt;
}

std::optional<Directivity> parse_directivity(std::string_view s) {
  for (Directivity v : {Directivity::normal, Directivity::reverse})
    if (name(v) == s) return v;
  return std::nullopt;
}

int body_count(const Case& c) {
  switch (c.scene) {
    case Scene::wall: return 1;
    case Scene::pair: return 2;
    case Scene::row3: return 3;
    case Scene::chain: return c.bodies;
  }
  return 0;
}
int contact_count(const Case& c) { return c.scene == Scene::wall ? 1 : body_count(c) - 1; }
bool uses_body1(Scene s) { return s != Scene::wall; }
bool uses_body2(Scene s) { return s == Scene::row3; }

namespace {
bool positive(double x) { return std::isfinite(x) && x > 0.0; }
}  // namespace

std::optional<std::string> validate(const Case& c) {
  if (!positive(c.pi2)) return "pi2: must be finite and > 0";
  if (!std::isfinite(c.pi3) || c.pi3 < 0.0) return "pi3: gap must be finite and >= 0";
  if (!std::isfinite(c.eps) || c.eps < 0.0 || c.eps > 1.0) return "eps: must be in [0, 1]";
  if (uses_body1(c.scene)) {
    if (!positive(c.pi5)) return "pi5: frequency ratio must be finite and > 0";
    if (!positive(c.pi6)) return "pi6: mass ratio must be finite and > 0";
  }
  if (uses_body2(c.scene)) {
    if (!positive(c.pi7)) return "pi7: frequency ratio must be finite and > 0";
    if (!positive(c.pi8)) return "pi8: mass ratio must be finite and > 0";
  }
  // The closed forms of the reference are those of an underdamped oscillator.
  if (c.scene == Scene::chain) {
    if (c.bodies < 2 || c.bodies > kMaxChainBodies)
      return "bodies: a chain needs 2 to " + std::to_string(kMaxChainBodies) + " bodies";
    if (!std::isfinite(c.kick)) return "kick: must be finite";
  } else {
    if (c.bodies != 0) return "bodies: only the chain scene has a body count";
    if (c.kick != 0.0) return "kick: only the chain scene starts moving";
  }
  if (!std::isfinite(c.xi) || c.xi < 0.0 || c.xi >= 1.0) return "xi: damping ratio must be in [0, 1)";
  if (!positive(c.n_free)) return "n_free: must be finite and > 0";
  if (!positive(c.a_p)) return "a_p: must be finite and > 0";
  if (!positive(c.w_p)) return "w_p: must be finite and > 0";
  return std::nullopt;
}

}  // namespace pb
