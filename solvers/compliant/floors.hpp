#pragma once
// The buildings scene (cases/buildings.hpp) as the compliant solver's two integrators read it
// (buildings_cvode.cpp, buildings_newmark.cpp): the floors' restoring and damping forces
// K u + C v from their nonzeros alone, the order the integrators store the floors in, and a
// contact element (kit/contact_elements/contact_law.hpp) at every floor pair of
// BuildingModel::contacts, acting on g = delta + u_right - u_left as the single oscillators'
// elements act on theirs (kit/contact_elements/elements.hpp): the same laws, onsets, rates.
//
// Stiffness (cases/README.md, "Buildings"): the Pi term K has the left building's equivalent
// oscillator as its unit, its total mass M_0 and its first mode w_1,0 (the masses and
// frequency the buildings' Pi terms give body 0): k = K M_0 w_1,0^2 for the linear element,
// k = K M_0 w_1,0^2 / sqrt(L) for the Hertz family (L as for the single oscillators), one k for
// every contact of the scene, as an engineer gives one element to every floor. With one storey
// each, M_0 w_1,0^2 is body 0's m0 w0^2: the single oscillators' pair and its element.
//
// Floor order: level by level (floor 1 of every building left to right, then floor 2, ...), so
// that a contact joins neighbours in the order and a storey joins floors as many apart as there
// are buildings at those levels: the equations' bandwidth is that of two or three buildings' storeys,
// whatever their height (with modal damping, whose C is full within a building, the band holds
// the building). With one storey each, the order is the single oscillators' pair's.

#include <span>
#include <vector>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "kit/contact_elements/contact_law.hpp"

namespace pb::compliant {

// k of every contact element of a buildings scene from the Pi term K (above).
double building_element_stiffness(const BuildingModel& md, Model model, double K);

class Floors {
 public:
  // One nonzero of row i of K and C: the column (a global floor) and the two entries.
  struct Entry {
    int col;
    double k, c;
  };

  Floors(const BuildingModel& md, Model model, double K);

  const BuildingModel& model() const { return md_; }
  int n() const { return md_.n_floors; }
  int nc() const { return static_cast<int>(laws_.size()); }
  double mass(int i) const { return md_.m(i); }
  // The level-by-level order: the floor stored at `slot`, and the slot of floor i.
  int floor_at(int slot) const { return order_[static_cast<std::size_t>(slot)]; }
  int slot_of(int i) const { return slot_[static_cast<std::size_t>(i)]; }
  // The widest coupling of K, C and the contacts, in slots.
  int half_band() const { return band_; }
  std::span<const Entry> row(int i) const {
    const auto b = static_cast<std::size_t>(start_[static_cast<std::size_t>(i)]);
    const auto e = static_cast<std::size_t>(start_[static_cast<std::size_t>(i) + 1]);
    return std::span<const Entry>(entries_).subspan(b, e - b);
  }
  // (K u)_i and (C v)_i, u and v in global floor order.
  double spring(int i, const double* u) const {
    double s = 0.0;
    for (const Entry& e : row(i)) s += e.k * u[e.col];
    return s;
  }
  double damper(int i, const double* v) const {
    double s = 0.0;
    for (const Entry& e : row(i)) s += e.c * v[e.col];
    return s;
  }

  // Contact j's floors (global indices), gap, penetration p = -g and its rate q = -g'.
  int left(int j) const { return md_.contacts[static_cast<std::size_t>(j)].i_left; }
  int right(int j) const { return md_.contacts[static_cast<std::size_t>(j)].i_right; }
  double gap(int j, const double* u) const { return md_.scene.delta + u[right(j)] - u[left(j)]; }
  double p(int j, const double* u) const { return -gap(j, u); }
  double q(int j, const double* v) const { return -(v[right(j)] - v[left(j)]); }

  bool closed(int j) const { return closed_[static_cast<std::size_t>(j)] != 0; }
  const Law& law(int j) const { return laws_[static_cast<std::size_t>(j)]; }
  double v_minus(int j) const { return v_minus_[static_cast<std::size_t>(j)]; }
  // The element's force on contact j (0 while it is open).
  double force(int j, const double* u, const double* v) const {
    return closed(j) ? law(j).force(p(j, u), q(j, v), v_minus(j)) : 0.0;
  }
  // Adds every closed element's force to the floors' forces f (+F on the right floor, -F on
  // the left one).
  void add_forces(const double* u, const double* v, double* f) const;
  // Contact j closes at time t at rate q (> 0: approaching, an impact, noted in `peaks`), or
  // opens.
  void close(int j, double q, double t, buildings::FloorPeaks& peaks);
  void open(int j) { closed_[static_cast<std::size_t>(j)] = 0; }

  // Why a finite state counts as diverged (kit/run_limits.hpp's bounds: |u| beyond 1e6 a_p /
  // w_p^2, or the energy beyond kDivergedEnergy times BuildingModel::energy_scale()), or null.
  const char* runaway(const double* u, const double* v) const;

 private:
  const BuildingModel& md_;
  std::vector<int> order_, slot_;
  int band_ = 0;
  std::vector<int> start_;  // row i's entries: [start_[i], start_[i + 1])
  std::vector<Entry> entries_;
  std::vector<Law> laws_;
  std::vector<char> closed_;
  std::vector<double> v_minus_;
  double floor_;  // the onset rate below which Hunt-Crossley's divisor is held (Elements::onset_rate)
};

}  // namespace pb::compliant
