#pragma once
// The MuJoCo model of a System, and MuJoCo's process set-up.
//
//   bodies    one body per building on a slide joint along x, its spring and dashpot the
//             joint's own stiffness and damping (MuJoCo's passive forces: its Euler and
//             implicit integrators treat the damping implicitly, as they are meant to, which
//             forces applied by hand would hide from them); no gravity.
//   contacts  a sphere per body, radius kRadius length units, spaced so that the distance
//             MuJoCo computes is the gap delta + u_R - u_L; the wall a plane through
//             -kRadius - delta with normal +x. An explicit <pair> per neighbouring contact
//             (condim 1: frictionless; every geom's contype and conaffinity 0, so nothing
//             else collides). Spheres this large make the normal exactly +x (centres on the
//             axis) and keep it so for any penetration below 2 kRadius.
//   load      -m a_g(t) into qfrc_applied from mjcb_control, which MuJoCo calls once per
//             evaluation of the dynamics (Euler and implicit: once per step at its start;
//             RK4: at each of its four stages, with d->time at the stage's own time).
//   units     faithful variants: the pulse's (length a_p / w_p^2, time 1 / w_p), so that
//             MuJoCo's absolute thresholds (mjMINVAL 1e-15, mjMAXVAL 1e10 on qpos, qvel and
//             qacc, beyond which it resets the state) never meet a case's scale; the
//             default variant: the case's own, as a new user would model it.
//
// Process set-up (prepare_process, once): mjcb_control, and handlers for MuJoCo's
// warnings and errors. Without them MuJoCo prints warnings and appends them to
// MUJOCO_LOG.TXT in the working directory, and exits the process on an error. Warnings
// are counted per thread and their first text kept for the run's message; an error throws
// (Debian's libmujoco is built with unwind tables) and ends that run as failed.
//
// Thread safety: each run compiles its own mjModel (its masses, springs and step are the
// run's), never changed after compilation, and its own mjData; mj_loadXML is serialised
// by a process-wide lock (MuJoCo 2.2.2 keeps the last loaded model in a global for
// mj_saveLastXML). The callback and handlers are process-wide function pointers set once;
// what they touch is thread-local (the running engine's Load, the warning count).

#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <vector>

#include "cases/system.hpp"
#include "solvers/mujoco/contact.hpp"
#include "solvers/mujoco/variants.hpp"

namespace pb::mujoco {

// Sphere radius in length units (a_p / w_p^2): penetrations up to 2000 of them keep the
// normal. Round-off on the gaps is that of coordinates up to (2 kRadius + delta) per body:
// 2.2e-16 x 2000 per body of a row, ~4e-11 a_p / w_p^2 at the end of a 100-body chain.
inline constexpr double kRadius = 1000.0;

// Installs mjcb_control and the warning and error handlers, once per process.
void prepare_process();

// Warnings MuJoCo raised on this thread since the last call, and the first one's text.
struct Warnings {
  long count = 0;
  std::string first;
};
Warnings take_warnings();

// Lengths and times of the model in the System's units.
struct Units {
  double length = 1.0;
  double time = 1.0;
};
Units units_of(const System& sys, const Config& config);

// The MJCF text of a System: step h_model (in model time), contacts as given.
std::string scene_xml(const System& sys, const Config& config, const Units& units, double h_model,
                      const ContactParameters* contact);

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

// Parses and compiles MJCF text from memory (a virtual file; nothing is read from disk).
// Null, with MuJoCo's message in `error`, when it does not compile.
ModelPtr compile(const std::string& xml, std::string& error);

// What mjcb_control calls on this thread while a LoadScope holds it: the single oscillators'
// Load below, the buildings' own (buildings.cpp).
class Control {
 public:
  virtual ~Control() = default;
  virtual void evaluate(const mjModel* m, mjData* d) = 0;
};

// What the control callback needs of the running engine: the load on each body per unit of
// the pulse's acceleration, and, per contact, which constraint row carried it at the
// previous evaluation (for the step's mean contact force).
class Load : public Control {
 public:
  Load(const System& sys, const Units& units, const std::vector<int>& contact_of_geom, int stages);

  // Before a step: forgets the last step's forces.
  void begin_step();
  // From mjcb_control: collects the previous evaluation's contact forces, notes this one's
  // rows, and writes the ground load at d->time into qfrc_applied.
  void evaluate(const mjModel* m, mjData* d) override;
  // After a step: collects the last evaluation's forces. False when MuJoCo evaluated the
  // dynamics another number of times than the integrator's stages.
  bool end_step(const mjData* d);

  // The step's mean contact force of contact j (model units), and whether MuJoCo reported
  // the contact at any evaluation of the step.
  double force(int j) const { return force_[static_cast<std::size_t>(j)]; }
  bool touched(int j) const { return touched_[static_cast<std::size_t>(j)] != 0; }

 private:
  void collect(const mjData* d);

  const System& sys_;
  LoadCursor load_;  // a_g at each evaluation (RK4's stages go back and forth within a step)
  Units units_;
  const std::vector<int>& contact_of_geom_;
  int stages_;
  int evaluations_ = 0;
  std::vector<double> mass_;    // per body
  std::vector<int> row_;        // per contact: its efc row at the last evaluation, or -1
  std::vector<double> force_;   // per contact
  std::vector<char> touched_;   // per contact
};

// Makes `load` the one the callback uses on this thread while it lives.
class LoadScope {
 public:
  explicit LoadScope(Control& load);
  ~LoadScope();
  LoadScope(const LoadScope&) = delete;
  LoadScope& operator=(const LoadScope&) = delete;

 private:
  Control* before_;
};

}  // namespace pb::mujoco
