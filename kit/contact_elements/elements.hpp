#pragma once
// The contact elements of one run, shared by both integrators: one Law per contact, which
// contacts are closed, the approach rate each began with, and the restitution of isolated
// contacts. Buffers are sized once; nothing here allocates per step.

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "cases/system.hpp"
#include "kit/contact_elements/contact_law.hpp"
#include "kit/isolated_restitution.hpp"
#include "kit/solver.hpp"

namespace pb::compliant {

// k of the element from the Pi term K (contact_law.hpp: linear, or Hertz family over sqrt(L),
// L = System::contact_length_scale()).
double element_stiffness(const System& sys, Model model, double K);

class Elements {
 public:
  Elements(const System& sys, Model model, double K);

  int size() const { return static_cast<int>(laws_.size()); }
  // Penetration p = -g and its rate q = -g' of contact j.
  double p(int j, const double* u) const { return -sys_.gap(j, u); }
  double q(int j, const double* v) const { return -sys_.gap_rate(j, v); }
  bool closed(int j) const { return closed_[ix(j)] != 0; }

  // The element's force on contact j (0 while it is open).
  double force(int j, const double* u, const double* v) const {
    if (!closed(j)) return 0.0;
    return laws_[ix(j)].force(p(j, u), q(j, v), v_minus_[ix(j)]);
  }
  // The element of contact j, and the approach rate its contact began with.
  const Law& law(int j) const { return laws_[ix(j)]; }
  double v_minus(int j) const { return v_minus_[ix(j)]; }
  // The rate a contact closing now at q is taken to have begun with: Hunt-Crossley divides
  // by it, so a grazing onset uses the restitution floor (below which no impact counts).
  double onset_rate(double q) const { return std::max(q, floor_); }

  // Adds every closed element's force to the bodies' forces f (+F on the right body, -F
  // on the left one).
  void add_forces(const double* u, const double* v, double* f) const;

  // Contact j closes at rate q (> 0: approaching), or opens at rate q. open() returns
  // whether it was an impact (closed while approaching).
  // t: when (the pounding's first impact and fastest approach, Result::first_impact).
  void close(int j, double q, double t);
  void open(int j, double q);
  // Impacts so far, and the restitution range of the isolated ones (into a Result).
  long impacts() const { return impacts_; }
  void finish(Result& r) const;

 private:
  const System& sys_;
  std::vector<Law> laws_;
  std::vector<char> closed_;
  double first_impact_ = std::numeric_limits<double>::quiet_NaN(), fastest_impact_ = 0.0;
  std::vector<char> isolated_;  // closed alone, and no other closed since
  std::vector<double> v_minus_;
  int n_closed_ = 0;
  long impacts_ = 0;
  double floor_;
  IsolatedRestitution restitution_;
};

}  // namespace pb::compliant
