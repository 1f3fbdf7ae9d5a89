#include "solvers/siconos/model.hpp"

#include <cmath>

#include "kit/run_limits.hpp"

namespace pb::siconos {

namespace engine {

double ground_sample(bool cosine, double amplitude, double t, double step) {
  return Pulse{cosine ? PulseShape::cosine : PulseShape::sine, amplitude, 1.0}.sample(t, step);
}

}  // namespace engine

namespace {

// A record or a pulse model for Siconos' load plugin: the case's own load (LoadCursor),
// sampled at step ends as Pulse::sample does, in the pulse's units.
class CaseLoad : public engine::GroundSampler {
 public:
  CaseLoad(const System& s, double sample_step)
      : pulse_(s.pulse), cursor_(pulse_), time_(1.0 / s.pulse.w), accel_(s.a_p), step_(sample_step) {}
  double operator()(double t) override { return cursor_.sample(t * time_, step_) / accel_; }

 private:
  Pulse pulse_;  // a copy (the record's samples shared), so the sampler outlives nothing it reads
  LoadCursor cursor_;
  double time_, accel_, step_;
};

}  // namespace

Units units_of(const System& s) { return {s.length_scale(), 1.0 / s.pulse.w}; }

engine::ModelSpec model_spec(const System& s, double sample_step, double t_end) {
  const Units units = units_of(s);
  const double t2 = units.time * units.time;
  engine::ModelSpec spec;
  const bool rest = s.u_start.size() != s.bodies.size() || s.v_start.size() != s.bodies.size();
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const Body& b = s.bodies[i];
    spec.bodies.push_back({b.m, b.k * t2, b.c * units.time, rest ? 0.0 : s.u_start[i] / units.length,
                           rest ? 0.0 : s.v_start[i] / units.velocity()});
  }
  for (int j = 0; j < s.n_contacts(); ++j) spec.contacts.push_back({s.left(j) == kWall ? -1 : s.left(j), s.right(j)});
  spec.delta = s.delta / units.length;
  spec.eps = s.eps;
  spec.cosine = s.pulse.shape == PulseShape::cosine;
  spec.amplitude = s.pulse.amplitude / s.a_p;
  spec.sample_step = sample_step / units.time;
  if (!s.pulse.paper()) spec.sampler = std::make_shared<CaseLoad>(s, sample_step);
  spec.t_end = t_end / units.time;
  return spec;
}

bool deadline_passed(void* deadline) { return static_cast<Deadline*>(deadline)->tick(); }

Result stopped(Status status, std::string message) {
  Result r;
  r.status = status;
  r.message = std::move(message);
  return r;
}

std::string check_system(const System& s) {
  for (const Body& b : s.bodies)
    if (!(b.m > 0.0) || !std::isfinite(b.m) || !std::isfinite(b.k) || !std::isfinite(b.c))
      return "every body needs a finite positive mass and a finite stiffness and damping";
  if (!std::isfinite(s.delta) || !std::isfinite(s.eps)) return "the gap and eps must be finite";
  const auto nb = s.bodies.size();
  if ((!s.u_start.empty() && s.u_start.size() != nb) || (!s.v_start.empty() && s.v_start.size() != nb))
    return "start state: needs one u and one v per body (or none: rest)";
  return {};
}

State::State(const System& s)
    : u(s.bodies.size()),
      v(u.size()),
      g(static_cast<std::size_t>(s.n_contacts())),
      rate(g.size()) {}

void State::update_gaps(const System& s) {
  for (int j = 0; j < s.n_contacts(); ++j) {
    g[static_cast<std::size_t>(j)] = s.gap(j, u.data());
    rate[static_cast<std::size_t>(j)] = s.gap_rate(j, v.data());
  }
}

bool State::finite() const {
  for (std::size_t i = 0; i < u.size(); ++i)
    if (!std::isfinite(u[i]) || !std::isfinite(v[i])) return false;
  return true;
}

void record(double t, const State& st, const std::vector<double>& force, std::vector<double>& out) {
  out.push_back(t);
  out.insert(out.end(), st.u.begin(), st.u.end());
  out.insert(out.end(), st.v.begin(), st.v.end());
  out.insert(out.end(), st.g.begin(), st.g.end());
  out.insert(out.end(), force.begin(), force.end());
}


}  // namespace pb::siconos
