#pragma once
// A pounding case in the paper's dimensionless terms (Dimitrakopoulos, Makris & Kappos
// 2009, eq. 8): the scene, the pulse, and the Pi terms. A Case is plain data; the one
// mapping to physical parameters is make_system() in system.hpp, so every solver receives
// the same physical scene for the same Case.

#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace pb {

// Bodies left to right (+x to the right); body 0 is the one whose response is reported.
//   wall: wall, 0        pair: 1, 0        row3: 1, 0, 2
//   chain: 0, 1, 2, ..., N-1 (Case::bodies = N); even-numbered bodies are like body 0,
//          odd-numbered ones take Pi5 and Pi6 (Pi5 = Pi6 = 1: a uniform chain)
enum class Scene { wall, pair, row3, chain };

// The ground acceleration (cases/README.md, "Pulses" and "Records"):
//   sine, cosine   the paper's: s a_p sin(w_p t) or s a_p cos(w_p t) on 0 <= t <= T_p, zero after
//   makris-a, -b   Makris' type-A and type-B pulses: the same accelerations as sine and cosine,
//                  solved through the general load (cases/load.hpp) rather than the paper's path
//   makris-c       Makris and Chang's type-Cn pulse, `cycles` = n: s a_p cos(w_p t + phi_n) on
//                  0 <= t <= (n + 1/2 - phi_n / pi) T_p
//   mp             Mavroeidis and Papageorgiou's (2003) pulse, `mp_gamma`, `mp_nu`
//   record         a recorded accelerogram (`record`), linear between its samples
enum class PulseShape { sine, cosine, makris_a, makris_b, makris_c, mp, record };

// The sign s of the pulse: +1 (normal) loads body 0 towards its left neighbour first.
enum class Directivity { normal, reverse };

std::string_view name(Scene s);
std::string_view name(PulseShape p);
std::string_view name(Directivity d);
std::optional<Scene> parse_scene(std::string_view s);
std::optional<PulseShape> parse_pulse(std::string_view s);
std::optional<Directivity> parse_directivity(std::string_view s);

struct Record;

// Whether Pi5/Pi6 (body 1, or the odd bodies of a chain) and Pi7/Pi8 (body 2) describe a
// body of the scene.
bool uses_body1(Scene s);
bool uses_body2(Scene s);

// The largest chain the case files accept.
inline constexpr int kMaxChainBodies = 1000;

// The physical values a case was given in (cases/physical.hpp), NaN where not given: periods
// (s), masses (kg), the gap (m). The Pi terms are the case; these say what the user typed.
struct Physical {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  double t0 = kNone, t1 = kNone, t2 = kNone;
  double m0 = kNone, m1 = kNone, m2 = kNone;
  double gap = kNone;
  // The yield displacements (m) of bodies 0, 1, 2 and of a chain's bodies, instead of
  // pi_y0 .. pi_y2, pi_y (cases/physical.hpp).
  double uy0 = kNone, uy1 = kNone, uy2 = kNone, uy = kNone;
};

// Every member has a default, so that a case can be written as designated initializers
// (`Case{.scene = Scene::wall}`) without -Wmissing-field-initializers.
struct Case {
  std::string family{};  // name of the sweep it belongs to; a label only
  Scene scene = Scene::pair;
  PulseShape pulse = PulseShape::sine;
  Directivity directivity = Directivity::normal;
  double pi2 = 1.0;  // w0 / w_p
  double pi3 = 0.5;  // delta w_p^2 / a_p
  double eps = 0.5;  // Pi4, coefficient of restitution
  double pi5 = 1.0;  // w0 / w1
  double pi6 = 1.0;  // m0 / m1
  double pi7 = 1.0;  // w0 / w2
  double pi8 = 1.0;  // m0 / m2
  // chain only: the number of bodies N (>= 2), and the velocity of body 0 (the left end)
  // at t = 0 towards +x, times w_p / a_p: a Newton's-cradle start. Every other scene,
  // and every other body, starts at rest.
  int bodies = 0;
  double kick = 0.0;
  double xi = 0.05;  // damping ratio of every body
  double n_free = 3.0;  // free-vibration periods T_max simulated after the pulse
  // Physical scale of the pulse. Pi1 does not depend on it (self-similarity); it exists
  // so that tests and the Fig. 3 family can check exactly that.
  double a_p = 1.0;
  double w_p = 1.0;
  // The loads beyond the paper's (cases/README.md): Makris-Chang Cn's number of cycles n;
  // the Mavroeidis-Papageorgiou pulse's gamma (> 1) and nu (degrees); a record's file, as
  // named (relative to the working directory), and its samples, read once by cases/ and
  // shared by every copy of the case (null for a case read back from a row).
  int cycles = 0;
  double mp_gamma = 0.0;
  double mp_nu = 0.0;
  std::string record{};
  std::shared_ptr<const Record> samples{};
  // A record scaled (cases/record_scale.hpp): record_scale is the factor on its accelerations,
  // given or found from the target peak ground acceleration pga (m/s^2) or the target
  // pseudo-spectral acceleration sa (m/s^2) at period sa_period (s, damping xi); samples hold
  // the scaled accelerations. NaN: no such target.
  double record_scale = 1.0;
  double pga = std::numeric_limits<double>::quiet_NaN();
  double sa = std::numeric_limits<double>::quiet_NaN();
  double sa_period = std::numeric_limits<double>::quiet_NaN();
  // Yielding (cases/README.md, "Yielding"): a body's restoring force is bilinear with
  // kinematic hardening, elastic up to its yield displacement u_y = Pi_y a_p / w_p^2, then
  // of stiffness alpha k. pi_y0, pi_y1, pi_y2 are those of bodies 0, 1, 2 (wall, pair,
  // row3), pi_y that of every body of a chain; infinity (the default) is elastic, today's
  // behaviour bit for bit. alpha, the post-yield stiffness ratio, is every body's.
  double pi_y0 = std::numeric_limits<double>::infinity();
  double pi_y1 = std::numeric_limits<double>::infinity();
  double pi_y2 = std::numeric_limits<double>::infinity();
  double pi_y = std::numeric_limits<double>::infinity();
  double alpha = 0.0;
  Physical physical{};  // what a physical case was given as; its Pi terms above follow from it
};

// Whether any body of the case yields (a finite Pi_y the scene uses).
bool yields(const Case& c);
// Pi_y of body 0 (the chain's pi_y): its ductility demand is Pi1 over it.
double pi_y_ref(const Case& c);

// Number of bodies (wall excluded) and of contacts of the case's scene.
int body_count(const Case& c);
int contact_count(const Case& c);

// The valid domain of a case (cases/README.md, "Valid domain"): what lies outside it
// would ask for more steps or events than a run can take, or for quantities that double
// precision cannot hold. The reasons for each number are in case.cpp.
inline constexpr double kMaxFrequencyContrast = 1e4;  // max/min over w_p and the bodies' w
inline constexpr double kMaxMassContrast = 1e6;       // max/min over the bodies' masses
inline constexpr double kMaxPeriodsPerRun = 1e6;      // t_end / t_min
inline constexpr double kMaxNFree = 1000;
inline constexpr double kMaxPi3 = 1e6;
inline constexpr double kMaxKick = 1e6;  // |kick|
inline constexpr double kMinAp = 1e-12, kMaxAp = 1e12;
inline constexpr double kMinWp = 1e-6, kMaxWp = 1e6;
inline constexpr double kMinRecordPeak = 1e-6, kMaxRecordPeak = 1e6;  // a record's peak over a_p
inline constexpr int kMaxCycles = 100;        // makris-c
inline constexpr double kMaxMpGamma = 100;    // mp: gamma in (1, 100]
inline constexpr double kMaxMpNu = 360;       // mp: |nu| <= 360 degrees
inline constexpr double kMinPiY = 1e-6;       // a yield displacement, over a_p / w_p^2

// Whether a pulse is the paper's own (sine, cosine), whose closed forms and step loads
// keep their own code, bit for bit as the stored baselines have them.
inline bool paper_pulse(PulseShape p) { return p == PulseShape::sine || p == PulseShape::cosine; }

// How long the load lasts, in periods T_p = 2 pi / w_p (an upper bound for makris-c).
double load_periods(const Case& c);

// The pulse scale alone: a_p in [kMinAp, kMaxAp], w_p in [kMinWp, kMaxWp] ("a_p: reason").
// validate() checks it too; a case in physical units checks it first, since its Pi terms are
// computed from a_p and w_p (cases/physical.hpp).
std::optional<std::string> check_scale(const Case& c);

// Checks every value the case uses, alone and in the contrasts and durations they imply.
// Returns "field: reason" for the first bad one; the reason names the bound.
std::optional<std::string> validate(const Case& c);


}  // namespace pb
