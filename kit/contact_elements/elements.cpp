#include "kit/contact_elements/elements.hpp"

#include <algorithm>
#include <cmath>

namespace pb::compliant {

double element_stiffness(const System& sys, Model model, double K) {
  const Body& b0 = sys.bodies[static_cast<std::size_t>(sys.ref)];
  const double linear = K * b0.m * b0.w * b0.w;
  return model == Model::kelvin_voigt ? linear : linear / std::sqrt(sys.contact_length_scale());
}

Elements::Elements(const System& sys, Model model, double K)
    : sys_(sys),
      closed_(static_cast<std::size_t>(sys.n_contacts()), 0),
      isolated_(static_cast<std::size_t>(sys.n_contacts()), 0),
      v_minus_(static_cast<std::size_t>(sys.n_contacts()), 0.0),
      floor_(kRestitutionFloor * sys.a_p / sys.pulse.w) {
  const double k = element_stiffness(sys, model, K);
  for (int j = 0; j < sys.n_contacts(); ++j) {
    const int l = sys.left(j), r = sys.right(j);
    const double m_left = l == kWall ? 0.0 : sys.bodies[ix(l)].m;
    laws_.push_back(make_law(model, k, sys.eps, m_left, sys.bodies[ix(r)].m));
  }
  // A body that starts overlapping its neighbour starts in contact.
  const std::vector<double> u = sys.u_start.empty() ? std::vector<double>(ix(sys.n_bodies()), 0.0) : sys.u_start;
  for (int j = 0; j < size(); ++j)
    if (p(j, u.data()) > 0.0) close(j, 0.0, 0.0);
}

void Elements::add_forces(const double* u, const double* v, double* f) const {
  for (int j = 0; j < size(); ++j) {
    if (!closed(j)) continue;
    const double F = force(j, u, v);
    f[ix(sys_.right(j))] += F;
    if (sys_.left(j) != kWall) f[ix(sys_.left(j))] -= F;
  }
}

void Elements::close(int j, double q, double t) {
  if (closed(j)) return;
  closed_[ix(j)] = 1;
  v_minus_[ix(j)] = onset_rate(q);
  if (q > 0.0) {
    ++impacts_;
    if (!(first_impact_ <= t)) first_impact_ = t;
    fastest_impact_ = std::max(fastest_impact_, q);
  }
  for (std::size_t i = 0; i < isolated_.size(); ++i) isolated_[i] = 0;  // nobody is alone now
  isolated_[ix(j)] = n_closed_ == 0 && q > floor_;
  ++n_closed_;
}

void Elements::open(int j, double q) {
  if (!closed(j)) return;
  closed_[ix(j)] = 0;
  --n_closed_;
  if (isolated_[ix(j)]) restitution_.add(-q / v_minus_[ix(j)]);
  isolated_[ix(j)] = 0;
}

void Elements::finish(Result& r) const {
  r.restitution_over_contacts = true;
  if (first_impact_ >= 0.0) note_impact(r, first_impact_, -fastest_impact_);
  restitution_.write(r);
}

}  // namespace pb::compliant
