#pragma once
// The two DART models of the buildings scene behind buildings.cpp's step loop, one per kind of
// variant (buildings.hpp): buildings_faithful.cpp and buildings_default.cpp. Each builds its
// world in its constructor (throwing std::runtime_error if DART refuses it, OutOfTime if the
// run's limit passes meanwhile) and steps it from t_k under the ground load at t_k.

#include <memory>
#include <vector>

#include "cases/buildings.hpp"
#include "kit/buildings_result.hpp"
#include "solvers/dart/run_limit.hpp"
#include "solvers/dart/variants.hpp"

namespace pb::dart {

class FloorsEngine {
 public:
  explicit FloorsEngine(const BuildingModel& md)
      : u_(static_cast<std::size_t>(md.n_floors), 0.0), v_(u_.size(), 0.0), entered_(md.contacts.size(), 0) {}
  virtual ~FloorsEngine() = default;
  FloorsEngine(const FloorsEngine&) = delete;
  FloorsEngine& operator=(const FloorsEngine&) = delete;

  // One World::step from t_k = k h under the ground acceleration a_g (m/s^2) at t_k, leaving
  // u(), v() and entered() at t_k+1. May throw OutOfTime (the run's limit, inside DART's step).
  // False where the run must stop: r's status and message say why (the step was taken).
  virtual bool step(long k, double a_g, buildings::BuildingsResult& r) = 0;
  // Engine notes added to the result's message (fallbacks, LCP warnings), once, at the end.
  virtual void finish(buildings::BuildingsResult& r) { (void)r; }

  // Per global floor (SI units): displacements and velocities.
  const std::vector<double>& u() const { return u_; }
  const std::vector<double>& v() const { return v_; }
  // Per contact (BuildingModel::contacts): 1 where it entered the contact set in the last step.
  const std::vector<char>& entered() const { return entered_; }

 protected:
  std::vector<double> u_, v_;
  std::vector<char> entered_;
};

std::unique_ptr<FloorsEngine> make_faithful_floors(const BuildingModel& md, const Config& config, const Settings& set,
                                                   double h, RunLimit& limit);
std::unique_ptr<FloorsEngine> make_default_floors(const BuildingModel& md, double h, RunLimit& limit);

// Appends a note to a result's message ("; " between notes).
void add_note(buildings::BuildingsResult& r, const std::string& note);

}  // namespace pb::dart
