#pragma once
// The four ways this project runs MuJoCo: an integrator (MuJoCo's semi-implicit Euler, its
// implicit-in-velocity Euler, its RK4) with contacts calibrated to eps (faithful), and
// MuJoCo's own defaults with only what a new user sets (default). Every value and the
// reason for it are in solvers/mujoco/README.md; the contact parameters are computed in one
// place, contact_parameters() in contact.cpp.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "kit/named_values.hpp"
#include "kit/solver.hpp"
#include "kit/variant_table.hpp"

namespace pb::mujoco {

enum class Integrator { euler, implicit, rk4 };

struct Config {
  std::string_view name;
  Integrator integrator = Integrator::euler;
  // true: every contact a spring-damper calibrated to eps, its time constant tied to the
  // step (Settings::contact_steps), in the units of the pulse; false: MuJoCo's defaults
  // (solref 0.02 1, solimp 0.9 0.95 0.001, margin 0) in the case's own units.
  bool calibrated = true;
};

inline constexpr VariantTable kVariants{
    std::array{
        Config{"euler-faithful", Integrator::euler, true},
        Config{"implicit-faithful", Integrator::implicit, true},
        Config{"rk4-faithful", Integrator::rk4, true},
        Config{"default", Integrator::euler, false},
    },
    "euler-faithful"};

// The contact time constant 1/w_c in steps when Settings::contact_steps is 0. Measured on
// the wall cases (README, "Calibration"): a stiffer contact (M = 1) scatters the
// restitution of isolated impacts more with the phase of the step (Euler, eps = 0.5:
// 0.33 to 0.70 at N = 256), a softer one (M = 4) lets the body's own spring act during
// the contact (0.57 to 0.92 at N = 64); M = 2 gives 0.43 to 0.54 at N = 256.
inline constexpr double kDefaultContactSteps = 2.0;
// Below one step the contact spring alone steps at w_c h > 1, half Euler's stability limit.
inline constexpr double kMinContactSteps = 1.0;
inline constexpr double kMaxContactSteps = 1e6;

// Settings::contact_steps, or the default when it is 0.
double contact_steps(const Settings& settings);

// An integrator's name in describe() and its words in `poundbench solvers`.
struct IntegratorWords {
  std::string_view name, summary;
};
IntegratorWords words(Integrator i);

// Every setting of the configuration, for describe() after the variant and the step.
void add_config(NamedValues& out, const Config& config, const Settings& settings);

// The named variants with one line each (`poundbench solvers`).
std::vector<VariantInfo> variant_list();

}  // namespace pb::mujoco
