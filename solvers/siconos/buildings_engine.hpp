#pragma once
// The buildings scene in Siconos (engine.cpp, the only file that includes Siconos; C++17 and
// plain data here, as engine.hpp): one LagrangianLinearTIDS per building with its full M, K
// and C, one Interaction per floor pair (LagrangianLinearTIR over the two buildings' floors,
// NewtonImpactNSL(eps)), TimeStepping with MoreauJeanOSI(theta, gamma) and Siconos' dense LCP.
// Everything in the pulse's units, as engine.hpp.

#include <memory>
#include <vector>

#include "solvers/siconos/engine.hpp"

namespace pb::siconos::engine {

struct BuildingSpec {
  int floors = 0;
  std::vector<double> m;     // floor masses (M is diagonal)
  std::vector<double> k, c;  // K and C, floors x floors, row by row
};

struct FloorPairSpec {
  int left = 0, right = 0;               // buildings (right = left + 1)
  int left_floor = 0, right_floor = 0;   // the floors within their buildings, from 0
};

struct BuildingsSpec {
  std::vector<BuildingSpec> buildings;  // left to right
  std::vector<FloorPairSpec> contacts;  // gap y = delta + u[right floor] - u[left floor]
  double delta = 0.0, eps = 0.0;
  // a_g(t), both in the pulse's units: F_ext = -M 1 a_g of every building is a load plugin
  // that calls it (through the body's z vector, as ModelSpec's sampler).
  std::shared_ptr<GroundSampler> sampler;
  double t_end = 0.0;
};

// TimeStepping with MoreauJeanOSI on the buildings, fixed step h.
class BuildingsStepper {
 public:
  BuildingsStepper(const BuildingsSpec& spec, double h, double theta, double gamma, bool enumeration);
  ~BuildingsStepper();
  BuildingsStepper(const BuildingsStepper&) = delete;
  BuildingsStepper& operator=(const BuildingsStepper&) = delete;

  // One step; false (and nothing done) when Siconos has no next step. Throws
  // std::runtime_error with Siconos' message.
  bool step();
  // The floors' displacements and velocities, building 0's first (the global numbering).
  void state(double* u, double* v) const;
  // Contact j is in the index set the coming step's LCP is built on.
  bool active(int j) const;
  // The LCP solver's info on the last step (0: solved, or no solver ran).
  int lcp_info() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pb::siconos::engine
