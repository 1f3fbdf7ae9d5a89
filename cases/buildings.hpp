#pragma once
// Multi-storey shear buildings in a row, pounding at their floor levels (the `buildings`
// scene; conventions in cases/README.md and the shared spec's "Buildings"). Plain data and
// its assembly: what the exact reference (solvers/buildings_reference/) and any other
// solver of the scene read.
//
//   Building        floor masses m_1..m_n (kg) and storey stiffnesses k_1..k_n (N/m), floor 1
//                   at the bottom; storey i joins floor i-1 to floor i, floor 0 is the ground.
//   BuildingScene   two or three buildings left to right, their damping (rayleigh or modal,
//                   ratio xi), the gap delta at rest, eps, the floors in contact, the load.
//   BuildingModel   the scene assembled: one global floor numbering (building 0's floors
//                   first, floor 1 first), M (diagonal), K (tridiagonal per building), C,
//                   each building's modes, the contacts, t_end and the scales.
//
// Coordinates are floor displacements u relative to the ground; every floor starts at rest.
// Equation of motion: M u'' + C u' + K u = -M 1 a_g(t) + W lambda, with the gap of the contact
// at floor j between buildings b (left) and b + 1 (right) g = delta + u_{b+1,j} - u_{b,j} and
// its column of W e_{b+1,j} - e_{b,j}.

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cases/load.hpp"

namespace pb {

// The tallest building the scene takes (its modes and the reference's matrices grow as the
// square of the floors).
inline constexpr int kMaxBuildingFloors = 100;

struct Building {
  std::vector<double> masses;       // floor 1 first (kg)
  std::vector<double> stiffnesses;  // storey 1 first (N/m)
  int floors() const { return static_cast<int>(masses.size()); }
};

// rayleigh: C = a0 M + a1 K with ratio xi in modes 1 and 2 (a one-storey building: mode 1
// twice, c = 2 xi w_1 m); modal: C = M Phi diag(2 xi w_r) Phi^T M, xi in every mode.
enum class BuildingDamping { rayleigh, modal };

struct BuildingScene {
  std::vector<Building> buildings;  // left to right: two or three
  BuildingDamping damping = BuildingDamping::rayleigh;
  double xi = 0.05;  // in [0, 1)
  double delta = 0.0;  // the gap at rest of every contact (m)
  double eps = 0.5;    // coefficient of restitution
  // The floors (numbered from 1) at which neighbours touch; empty: every floor both have.
  // A floor named must exist in every building (with three buildings, the middle one touches
  // both neighbours at it).
  std::vector<int> contact_floors;
  bool no_contact = false;  // every contact removed (the no-contact response)
  Pulse pulse;              // the ground acceleration, signed by the directivity
  // The pulse's scales, which every tolerance and Pi term is relative to (L = a_p / w_p^2,
  // V = a_p / w_p): 0 takes them from the pulse (|amplitude| and w; a record's peak |a_g|).
  double a_p = 0.0;
  double w_p = 0.0;
  // Duration: t_end > 0 as given; 0 takes T_p (a record: its length) + n_free T_1, T_1 the
  // longest first period of the buildings.
  double t_end = 0.0;
  double n_free = 3.0;
};

// Why a scene cannot be solved, in one line ("" when it can): two or three buildings, each
// with floors, positive finite masses and stiffnesses, xi in [0, 1), delta >= 0, eps in
// [0, 1], contact floors that both neighbours have (no repeats), a finite positive t_end
// (or 0), n_free > 0, positive scales.
std::string validate(const BuildingScene& scene);

struct FloorContact {
  int left = 0, right = 0;  // buildings, numbered from 0 (right = left + 1)
  int floor = 1;            // numbered from 1
  int i_left = 0, i_right = 0;  // the two floors' global indices
};

// A building's modes, from K phi = w^2 M phi: w ascending, Phi mass-normalised
// (Phi^T M Phi = I), and the damping ratio each mode has (rayleigh: a0 / (2 w_r) + a1 w_r / 2,
// which exceeds 1 in high modes of a heavily damped tall building; modal: xi).
struct BuildingModes {
  Eigen::VectorXd w;
  Eigen::MatrixXd phi;  // columns are modes, floor 1 first
  Eigen::VectorXd xi;
};

struct BuildingModel {
  BuildingScene scene;
  int n_floors = 0;                // all buildings
  std::vector<int> first;          // global index of each building's floor 1
  std::vector<int> building_of;    // per global floor
  Eigen::VectorXd m;               // floor masses
  Eigen::VectorXd k;               // per global floor i: the stiffness of the storey below it
  Eigen::MatrixXd K, C;            // block diagonal, one block per building
  std::vector<BuildingModes> modes;  // per building
  std::vector<FloorContact> contacts;  // left to right, floor 1 first within a pair
  double t_end = 0.0;
  double t_min = 0.0;  // min(T_p, the shortest natural period of any building)
  double a_p = 1.0, w_p = 1.0;  // the scales (never 0 here)
  double length_scale() const { return a_p / (w_p * w_p); }
  double speed_scale() const { return a_p / w_p; }
  // Kinetic plus elastic energy of a state (floor displacements and velocities).
  double energy(const double* u, const double* v) const;
  // The kinetic energy of every floor moving at a_p / w_p: what energy errors are relative to.
  double energy_scale() const;
  int global(int building, int floor) const { return first[static_cast<std::size_t>(building)] + floor - 1; }
};

// The building's modes alone (masses and stiffnesses valid). Its frequencies are the singular
// values of G = diag(sqrt k) B M^-1/2 (B the difference matrix that gives the drifts), so that
// K = B^T diag(k) B is never formed: a tall building's low frequencies keep their relative
// accuracy (an eigensolver on K loses the ratio w_max^2 / w_1^2 of theirs).
BuildingModes building_modes(const Building& b);

// Rayleigh's a0, a1 for ratio xi in modes w1, w2 (a one-storey building: w2 = w1).
void rayleigh_coefficients(double xi, double w1, double w2, double& a0, double& a1);

// The scene assembled (it must validate).
BuildingModel assemble(const BuildingScene& scene);

// A contact element's stiffness k on the scene for the Pi term K of --stiffness (cases/README.md,
// "Buildings"): K times the left building's total mass times its first mode squared (N/m),
// for a Hertz-type element over the square root of the length scale (N/m^1.5; a record's own
// length scale, as for the single oscillators). K = 1 gives the unit that --k-contact divides by.
double contact_element_stiffness(const BuildingModel& model, bool hertz, double K = 1.0);

// A uniform building: n floors of mass m, every storey of the stiffness that gives first mode
// w1, k = m (w1 / (2 sin(pi / (2 (2n + 1)))))^2.
Building uniform_building(int floors, double mass, double w1);

// The uniform buildings' Pi-term form (cases/README.md, "Buildings"): the left building's
// w_1 = pi2 w_p, delta = pi3 a_p / w_p^2, eps = pi4, the right building's w_1 = w_1,left / pi5,
// total masses left over right pi6 (the left building's floors of unit mass: it cancels).
// The load is the pulse given (its a_p, w_p are the scales).
BuildingScene uniform_pair(int floors_left, int floors_right, double pi2, double pi3, double pi4, double pi5,
                           double pi6, const Pulse& pulse, double a_p, double w_p);

}  // namespace pb
