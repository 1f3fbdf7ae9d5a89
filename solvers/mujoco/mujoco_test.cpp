// MuJoCo's own facts (solvers/mujoco/): the calibration of its soft contacts to eps, the
// restitution they give per integrator and contact time constant, the contact forces of
// the history, warnings kept out of the output and the working directory, the default
// variant's parameters, and runs on two threads at once. The facts every solver shares
// are in solver_contract_test.cpp.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "solvers/mujoco/contact.hpp"
#include "solvers/mujoco/model.hpp"
#include "solvers/mujoco/mujoco_solver.hpp"
#include "kit/testing.hpp"
#include "solvers/registry.hpp"

namespace pb {
// Named, not anonymous: the unity build puts this file beside others with helpers of the same names.
namespace mujoco_tests {

using test::make_case;
using test::sci;

// ---------------------------------------------------------------- calibration

// The clamped linear oscillator (Schwager & Poeschel): eps = 0.5 needs zeta = 0.2553, and
// the textbook zeta = -ln(eps) / sqrt(pi^2 + ln(eps)^2) = 0.2155, which ends the contact at
// g = 0, gives 0.55 once the force is clamped. The inverse is exact to its bisection.
TEST(MujocoCalibration, ClampedOscillatorNeedsZeta0_2553ForHalfRestitution) {
  EXPECT_NEAR(mujoco::damping_ratio(0.5), 0.2553, 5e-5);
  const double textbook = -std::log(0.5) / std::sqrt(M_PI * M_PI + std::log(0.5) * std::log(0.5));
  EXPECT_NEAR(textbook, 0.2155, 5e-5);
  EXPECT_NEAR(mujoco::clamped_restitution(textbook), 0.55, 0.005);
  EXPECT_NEAR(mujoco::clamped_restitution(1.0), std::exp(-2.0), 1e-15);  // the two branches meet
  EXPECT_NEAR(mujoco::clamped_restitution(1.0 - 1e-9), std::exp(-2.0), 1e-7);
  EXPECT_NEAR(mujoco::clamped_restitution(1.0 + 1e-9), std::exp(-2.0), 1e-7);
  for (double eps : {1e-3, 0.1, 0.135, 0.5, 0.9, 0.999})
    EXPECT_NEAR(mujoco::clamped_restitution(mujoco::damping_ratio(eps)), eps, 1e-12 * std::max(1.0, eps)) << eps;
  EXPECT_EQ(mujoco::damping_ratio(1.0), 0.0);
  EXPECT_TRUE(std::isinf(mujoco::damping_ratio(0.0)));
}

// A wall and one body, stepped once into a penetration, as MuJoCo sets up its row.
struct WallModel {
  mujoco::ModelPtr model;
  mujoco::DataPtr data;
};

WallModel wall_model(const mujoco::ContactParameters& contact, double mass) {
  mujoco::prepare_process();
  Case c = make_case(Scene::wall, PulseShape::sine, 1.0, 1.0, 0.5);
  System sys = make_system(c);
  sys.bodies[0].m = mass;
  const mujoco::Config config = *mujoco::kVariants.find("euler-faithful");
  std::string error;
  WallModel w;
  w.model = mujoco::compile(mujoco::scene_xml(sys, config, mujoco::units_of(sys, config), 0.01, &contact), error);
  EXPECT_TRUE(w.model) << error;
  if (w.model) w.data.reset(mj_makeData(w.model.get()));
  return w;
}

// diagApprox, MuJoCo's estimate of the row's A = 1/m, is A/3 for a body on one slide joint
// (the mean over three directions), so the share of aref the solver delivers is
// de = A / (A + R) = 3d / (1 + 2d) exactly; calibrated_contact() divides it out, so the
// row's effective stiffness and damping are w_c^2 and 2 zeta w_c.
TEST(MujocoCalibration, EffectiveImpedanceIsThreeDOverOnePlusTwoD) {
  const double h = 0.01, steps = 2.0, mass = 2.0;
  const mujoco::ContactParameters p = mujoco::calibrated_contact(0.5, steps, h);
  WallModel w = wall_model(p, mass);
  ASSERT_TRUE(w.data);
  w.data->qpos[0] = -0.5 - 1e-3;  // 1e-3 into the wall (Pi3 = 0.5, in units of the pulse)
  mj_forward(w.model.get(), w.data.get());
  ASSERT_EQ(w.data->nefc, 1);
  const double A = 1.0 / mass, d = mujoco::kImpedance;
  EXPECT_NEAR(w.data->efc_diagApprox[0], A / 3.0, 1e-15);
  const double de = A / (A + w.data->efc_R[0]);
  EXPECT_NEAR(de, 3.0 * d / (1.0 + 2.0 * d), 1e-12);
  EXPECT_NEAR(de, mujoco::effective_impedance(d), 1e-12);
  // Effective stiffness and damping of the row: de times MuJoCo's K imp and B.
  const double w_c = 1.0 / (steps * h), zeta = mujoco::damping_ratio(0.5);
  EXPECT_NEAR(de * w.data->efc_KBIP[0] * w.data->efc_KBIP[2], w_c * w_c, 1e-9 * w_c * w_c);
  EXPECT_NEAR(de * w.data->efc_KBIP[1], 2.0 * zeta * w_c, 1e-9 * w_c);
}

// ---------------------------------------------------------------- restitution

// A free body (no spring, no damper, no load) thrown at the wall at 1, its gap at the
// start offset by a fraction of a step so that the contact begins at every phase of the
// step: the restitution range over 16 phases.
struct Range {
  double low = 1e300, high = -1e300;
  double sum = 0.0;  // of the restitutions, for their mean
  int impacts = 0;
};

Range free_impacts(std::string_view variant, double eps, double contact_steps, int phases = 16) {
  Range r;
  const int n_steps = 256;
  for (int phase = 0; phase < phases; ++phase) {
    System s;
    s.wall = true;
    s.bodies = {Body{1.0, 0.0, 0.0, 0.0}};
    s.eps = eps;
    s.pulse.amplitude = 0.0;
    s.t_min = 1.0;
    const double h = s.t_min / n_steps;
    s.delta = (3.0 + static_cast<double>(phase) / phases) * h;
    s.u_start = {0.0};
    s.v_start = {-1.0};
    s.t_end = (20.0 + 60.0 * contact_steps) * h;
    Settings st;
    st.variant = variant;
    st.steps = n_steps;
    st.contact_steps = contact_steps;
    const Result res = mujoco::solve(s, st);
    EXPECT_EQ(res.status, Status::ok) << res.message;
    if (res.isolated_impacts != 1) {
      ADD_FAILURE() << variant << " eps=" << eps << " M=" << contact_steps << " phase " << phase << ": "
                    << res.isolated_impacts << " isolated impacts";
      continue;
    }
    r.low = std::min(r.low, res.restitution_low);
    r.high = std::max(r.high, res.restitution_high);
    r.sum += res.restitution_low;
    ++r.impacts;
  }
  return r;
}

// What each integrator gives for eps = 0.5 and 1 at contact time constants of 1 to 8 steps,
// measured over the 16 phases (the bounds are the measured ranges widened by 0.005, room
// for another libm's round-off in so few operations). The scatter is the finding: the
// contact starts wherever in a step the gap closes, which moves the spring's phase by up
// to a step, and shrinks with M only as the contact stays longer (Euler, eps = 0.5:
// 0.33-0.62 at M = 1, 0.45-0.55 at 2, 0.48-0.53 at 4, 0.49-0.52 at 8). eps = 0 (a damper
// of rate 1/h) stops the approach in one Euler step: e = 0 at every phase.
TEST(MujocoRestitution, IsolatedImpactsScatterAroundEpsWithThePhaseOfTheStep) {
  struct Expect {
    std::string_view variant;
    double eps, steps, low, high;
  };
  const std::vector<Expect> table = {
      {"euler-faithful", 0.0, 2, 0.0, 0.0},        {"euler-faithful", 0.0, 8, 0.0, 0.0},
      {"euler-faithful", 0.5, 1, 0.3306, 0.7393},  {"euler-faithful", 0.5, 2, 0.4246, 0.5585},
      {"euler-faithful", 0.5, 4, 0.4648, 0.5293},  {"euler-faithful", 0.5, 8, 0.4816, 0.5127},
      {"euler-faithful", 1.0, 1, 1.0000, 1.0000},  {"euler-faithful", 1.0, 2, 0.9799, 1.0222},
      {"euler-faithful", 1.0, 4, 0.9932, 1.0079},  {"euler-faithful", 1.0, 8, 0.9992, 1.0008},
      // The same motion: MuJoCo 2.2.2's Euler already integrates joint damping implicitly.
      {"implicit-faithful", 0.5, 2, 0.4246, 0.5585}, {"implicit-faithful", 1.0, 2, 0.9799, 1.0222},
      // RK4 never ends a free body's plastic contact (its damper decays by the RK4
      // polynomial at b h = 1, 0.375 per step, never to zero), so eps = 0 has no isolated
      // impact to measure here.
      {"rk4-faithful", 0.5, 1, 0.4522, 0.6174},    {"rk4-faithful", 0.5, 2, 0.4698, 0.5488},
      {"rk4-faithful", 0.5, 4, 0.4836, 0.5224},    {"rk4-faithful", 0.5, 8, 0.4916, 0.5111},
      {"rk4-faithful", 1.0, 1, 0.9545, 1.0163},    {"rk4-faithful", 1.0, 2, 0.9877, 1.0124},
      {"rk4-faithful", 1.0, 4, 0.9969, 1.0032},    {"rk4-faithful", 1.0, 8, 0.9995, 1.0006},
  };
  for (const Expect& e : table) {
    const Range r = free_impacts(e.variant, e.eps, e.steps);
    RecordProperty(std::string(e.variant) + "_eps" + sci(e.eps) + "_M" + sci(e.steps), sci(r.low) + ".." + sci(r.high));
    EXPECT_EQ(r.impacts, 16);
    EXPECT_GE(r.low, e.low - 0.005) << e.variant << " eps=" << e.eps << " M=" << e.steps;
    EXPECT_LE(r.high, e.high + 0.005) << e.variant << " eps=" << e.eps << " M=" << e.steps;
  }
}

// "eps on average" measured (issue 32): the mean over 64 phases of the step, eps = 0.5 and
// the default M = 2. RK4's is eps to 0.0012 (measured 0.5012); Euler's (and so implicit's)
// is low, 0.4865, and nears eps only as M grows (0.4920 at M = 4, 0.4957 at 8): the
// phases where the contact starts late in a step lose more than the early ones gain. The
// README quotes these numbers from this test's properties (the bounds: the measured means
// widened by 0.002, another libm's round-off).
TEST(MujocoRestitution, TheMeanOverTheStepsPhasesIsEpsForRk4AndLowForEuler) {
  const Range euler = free_impacts("euler-faithful", 0.5, 2, 64), rk4 = free_impacts("rk4-faithful", 0.5, 2, 64);
  ASSERT_EQ(euler.impacts, 64);
  ASSERT_EQ(rk4.impacts, 64);
  const double euler_mean = euler.sum / 64, rk4_mean = rk4.sum / 64;
  RecordProperty("euler_mean_eps0.5_M2", sci(euler_mean));
  RecordProperty("rk4_mean_eps0.5_M2", sci(rk4_mean));
  EXPECT_NEAR(euler_mean, 0.4865, 0.002);
  EXPECT_NEAR(rk4_mean, 0.5012, 0.002);
}

// ---------------------------------------------------------------- forces, warnings, variants

// The history's contact force is the step's impulse over h: for a free body against the
// wall, m (v_k+1 - v_k) = h lambda at every step, for RK4 too (the four stages' forces
// weighted as RK4 weights their accelerations), which also shows that efc_force still holds
// a stage's forces when the next stage's control callback reads them. Round-off only: 1e-12
// of the approach momentum.
TEST(MujocoForces, HistoryForcesAreTheContactImpulseOfEachStep) {
  for (std::string_view variant : {"euler-faithful", "rk4-faithful", "implicit-faithful"}) {
    System s;
    s.wall = true;
    s.bodies = {Body{2.0, 0.0, 0.0, 0.0}};
    s.eps = 0.5;
    s.pulse.amplitude = 0.0;
    s.t_min = 1.0;
    s.delta = 2.5 / 64.0;
    s.u_start = {0.0};
    s.v_start = {-1.0};
    s.t_end = 40.0 / 64.0;
    Settings st;
    st.variant = variant;
    st.steps = 64;
    st.history_samples = 1;
    const Result r = mujoco::solve(s, st);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    const History& hist = r.history;
    ASSERT_EQ(hist.row_size(), 5);  // t, u, v, g, lambda
    const double h = r.step;
    double worst = 0.0, impulse = 0.0;
    for (std::size_t k = 1; k < hist.rows(); ++k) {
      const double* before = &hist.data[(k - 1) * 5];
      const double* after = &hist.data[k * 5];
      worst = std::max(worst, std::abs(2.0 * (after[2] - before[2]) - h * after[4]));
      impulse += h * after[4];
    }
    RecordProperty(std::string(variant), sci(worst));
    EXPECT_LT(worst, 1e-12 * 2.0) << variant;
    ASSERT_EQ(r.isolated_impacts, 1);
    EXPECT_NEAR(impulse, 2.0 * (1.0 + r.restitution_low), 1e-12) << variant << ": (1 + e) m v0 over the contact";
  }
}

// A mixed solref (timeconst > 0, damping < 0) is refused by MuJoCo on every step it
// meets the contact ("mixed solref format, replacing with default"): the handlers count it
// and print nothing, and no MUJOCO_LOG.TXT appears in the working directory.
TEST(MujocoWarnings, MixedSolrefWarnsEveryStepCountedNotPrintedNorLogged) {
  const std::filesystem::path log = std::filesystem::current_path() / "MUJOCO_LOG.TXT";
  const bool had_log = std::filesystem::exists(log);
  mujoco::ContactParameters mixed = mujoco::default_contact();
  mixed.solref = {0.02, -1.0};
  WallModel w = wall_model(mixed, 1.0);
  ASSERT_TRUE(w.data);
  (void)mujoco::take_warnings();
  w.data->qpos[0] = -0.5 - 1e-3;
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  for (int k = 0; k < 10; ++k) {
    w.data->qpos[0] = -0.5 - 1e-3;  // in contact at every step
    mj_step(w.model.get(), w.data.get());
  }
  const std::string out = testing::internal::GetCapturedStdout(), err = testing::internal::GetCapturedStderr();
  const mujoco::Warnings warned = mujoco::take_warnings();
  EXPECT_EQ(warned.count, 10);
  EXPECT_NE(warned.first.find("mixed solref"), std::string::npos) << warned.first;
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
  if (!had_log) {
    EXPECT_FALSE(std::filesystem::exists(log));
  }
}

// The default variant leaves MuJoCo's contact parameters alone: what its model gets is
// MuJoCo 2.2.2's defaults, as default_contact() and describe() say.
TEST(MujocoVariants, DefaultVariantHasMujocosOwnContactParameters) {
  mujoco::prepare_process();
  const System sys = make_system(make_case(Scene::pair, PulseShape::sine, 1.0, 0.5, 0.5));
  const mujoco::Config config = *mujoco::kVariants.find("default");
  std::string error;
  const mujoco::ModelPtr m = mujoco::compile(mujoco::scene_xml(sys, config, mujoco::units_of(sys, config), 0.01, nullptr), error);
  ASSERT_TRUE(m) << error;
  ASSERT_EQ(m->npair, 1);
  const mujoco::ContactParameters p = mujoco::default_contact();
  for (int i = 0; i < 2; ++i) EXPECT_EQ(m->pair_solref[i], p.solref[static_cast<std::size_t>(i)]);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(m->pair_solimp[i], p.solimp[static_cast<std::size_t>(i)]);
  EXPECT_EQ(m->pair_margin[0], 0.0);
  EXPECT_EQ(m->pair_gap[0], 0.0);
  EXPECT_EQ(m->opt.integrator, mjINT_EULER);
  EXPECT_EQ(m->pair_dim[0], 1);
}

TEST(MujocoVariants, ContactStepsIsCheckedAndDescribedByTheFaithfulVariantsOnly) {
  Settings st;
  st.contact_steps = 0.5;
  EXPECT_EQ(mujoco::check(st).rfind("contact_steps:", 0), 0u) << mujoco::check(st);
  st.contact_steps = std::nan("");
  EXPECT_EQ(mujoco::check(st).rfind("contact_steps:", 0), 0u);
  st.contact_steps = 8;
  EXPECT_EQ(mujoco::check(st), "");
  EXPECT_NE(mujoco::describe(st).find("\"contact_steps\":8"), std::string::npos) << mujoco::describe(st);
  st.contact_steps = 0;
  EXPECT_NE(mujoco::describe(st).find("\"contact_steps\":2"), std::string::npos) << mujoco::describe(st);
  const SolverInfo* solver = find_solver("mujoco");
  ASSERT_NE(solver, nullptr);
  const auto used = settings_used(*solver, "rk4-faithful");
  EXPECT_NE(std::find(used.begin(), used.end(), "contact_steps"), used.end());
  const auto used_default = settings_used(*solver, "default");
  EXPECT_EQ(std::find(used_default.begin(), used_default.end(), "contact_steps"), used_default.end());
}

// ---------------------------------------------------------------- runs

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

std::vector<System> some_systems() {
  std::vector<System> out;
  for (Scene scene : {Scene::wall, Scene::pair, Scene::row3})
    for (PulseShape p : {PulseShape::sine, PulseShape::cosine})
      for (double eps : {0.0, 0.5, 1.0}) out.push_back(make_system(make_case(scene, p, 0.8, 0.5, eps)));
  return out;
}

// One model per run, never changed once compiled, and one mjData per run: two threads
// solving the same cases at once give the serial answers bit for bit (the control callback
// and warning handlers are process-wide, what they touch thread-local).
TEST(MujocoThreads, TwoThreadsAtOnceGiveTheSerialAnswersBitForBit) {
  const std::vector<System> systems = some_systems();
  for (std::string_view variant : {"euler-faithful", "rk4-faithful", "default"}) {
    Settings st;
    st.variant = variant;
    std::vector<Result> serial;
    for (const System& s : systems) serial.push_back(mujoco::solve(s, st));
    std::vector<Result> a(systems.size()), b(systems.size());
    std::thread one([&] {
      for (std::size_t i = 0; i < systems.size(); ++i) a[i] = mujoco::solve(systems[i], st);
    });
    std::thread two([&] {
      for (std::size_t i = systems.size(); i-- > 0;) b[i] = mujoco::solve(systems[i], st);
    });
    one.join();
    two.join();
    for (std::size_t i = 0; i < systems.size(); ++i) {
      ASSERT_EQ(serial[i].status, Status::ok) << serial[i].message;
      for (const Result* r : {&a[i], &b[i]}) {
        EXPECT_EQ(bits(r->pi1), bits(serial[i].pi1)) << variant << " " << i;
        EXPECT_EQ(r->impacts, serial[i].impacts);
        EXPECT_EQ(bits(r->restitution_low), bits(serial[i].restitution_low));
        EXPECT_EQ(bits(r->min_gap), bits(serial[i].min_gap));
      }
    }
  }
}

// In the units of the pulse, a case scaled by powers of two is the same model: the faithful
// variants' Pi1 is the same to the bit. The default variant, in the case's units, is not
// (MuJoCo's time constant 0.02 is absolute): its Pi1 moved by 2.0e-4 relative here.
TEST(MujocoSelfSimilarity, FaithfulVariantsGiveTheSamePi1AtEveryPulseScale) {
  Case c = make_case(Scene::pair, PulseShape::cosine, 0.8, 0.5, 0.5);
  Settings faithful, def;
  def.variant = "default";
  const double pi1 = mujoco::solve(make_system(c), faithful).pi1;
  const double pi1_default = mujoco::solve(make_system(c), def).pi1;
  double moved = 0.0;
  for (double scale : {0.25, 4.0, 1024.0}) {
    Case s = c;
    s.a_p = scale;
    s.w_p = 1.0 / scale;
    EXPECT_EQ(bits(mujoco::solve(make_system(s), faithful).pi1), bits(pi1)) << scale;
    moved = std::max(moved, std::abs(mujoco::solve(make_system(s), def).pi1 / pi1_default - 1.0));
  }
  RecordProperty("default_moved", sci(moved));
  EXPECT_GT(moved, 1e-5);
}

// MuJoCo 2.2.2's Euler integrates joint damping implicitly, and the joint dampers are the
// only velocity-dependent forces here: its implicit integrator takes the same steps, Pi1
// equal to round-off (measured to the bit on these 18 cases; 1e-12 allows another libm).
TEST(MujocoIntegrators, ImplicitTakesEulersStepsWhereOnlyJointsAreDamped) {
  Settings euler, implicit;
  implicit.variant = "implicit-faithful";
  double worst = 0.0;
  int same = 0;
  for (const System& s : some_systems()) {
    const Result a = mujoco::solve(s, euler), b = mujoco::solve(s, implicit);
    ASSERT_EQ(a.status, Status::ok) << a.message;
    worst = std::max(worst, std::abs(b.pi1 - a.pi1) / a.pi1);
    if (a.pi1 == b.pi1) ++same;
  }
  // The same motion, but not the same operations: Pi1 equal to the bit on 8 of the 18 cases,
  // the others within 1.3e-14 (issue 32: README had "equal to the bit"); 1e-12 leaves room.
  RecordProperty("worst", sci(worst));
  RecordProperty("equal_bit_for_bit", std::to_string(same) + " of " + std::to_string(some_systems().size()));
  EXPECT_LT(worst, 1e-12);
}

}  // namespace mujoco_tests
}  // namespace pb
