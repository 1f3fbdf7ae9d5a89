#pragma once
// MuJoCo's contact as a spring-damper, and its calibration to a coefficient of restitution.
//
// MuJoCo has no restitution. A contact row asks the constraint solver for the reference
// acceleration aref = -b g' - k d g (g the signed distance, d the impedance of solimp), and
// the solver delivers a share de of it, de = A / (A + R), R = (1 - d) / d * diagApprox;
// the rest of the row's free acceleration, (1 - de) a0, goes through. Its force is clamped
// at zero (a contact pushes, never pulls). So an isolated contact is the clamped linear
// oscillator g'' + 2 zeta w_c g' + w_c^2 g = 0 (w_c^2 = de d k, 2 zeta w_c = de b) that
// ends when its force returns to zero, before the gap does (Schwager & Poeschel 2007).
// Its restitution depends on zeta alone (clamped_restitution): zeta = 0.2553 for eps = 0.5,
// not the 0.2155 of the textbook ln(eps) formula, which ends the contact at g = 0 and gives
// 0.55 here.
//
// diagApprox is MuJoCo's estimate of the row's A from the bodies' invweight0, the mean of
// the three translational directions: a body on one slide joint moves in one of them, so
// diagApprox = A / 3 exactly and de = 3d / (1 + 2d) (0.99664 for d = 0.99; measured from
// efc_R and efc_diagApprox, solvers/mujoco/mujoco_test.cpp). calibrated_contact() divides it out.
//
// The direct form of solref (-k, -b) is used, not (timeconst, dampratio): dampratio = 0
// (eps = 1) is an infinitely stiff spring there, and a zero spring (eps = 0, a pure damper)
// has no time constant. Both entries stay <= 0: a mixed pair (timeconst > 0, -b) is
// "mixed solref format", which MuJoCo replaces with its default and warns about on every
// step. The direct form also bypasses refsafe (the time constant raised to 2h), which
// applies to the positive form only.

#include <array>

namespace pb::mujoco {

// The restitution of the clamped linear oscillator with damping ratio zeta >= 0:
// exp(-zeta phi / s), s = sqrt(1 - zeta^2), phi = atan2(2 zeta s, 2 zeta^2 - 1) when
// underdamped; (zeta + s')^(-2 zeta / s'), s' = sqrt(zeta^2 - 1), when overdamped; e^-2 at 1.
double clamped_restitution(double zeta);
// Its inverse on eps in (0, 1] (1 gives 0), to 1e-14 relative; infinity for eps <= 0.
double damping_ratio(double eps);

// The impedance of the calibrated contacts (solimp = d d width: constant over the
// penetration). Near hard: 1 - de = 0.0034 of a row's free acceleration leaks through.
inline constexpr double kImpedance = 0.99;

// The effective impedance de of a contact row of bodies on slide joints (see above).
double effective_impedance(double d);

// A contact pair's parameters as MJCF attributes take them.
struct ContactParameters {
  std::array<double, 2> solref{};
  std::array<double, 5> solimp{};
  double margin = 0.0;
  double gap = 0.0;
};

// The contact whose isolated impact restitutes eps, for a step h (model time): damping
// ratio zeta = damping_ratio(eps) and natural frequency w_c = 1 / (M h) (M = contact
// steps), lowered to 1 / (2 zeta h) where that is less, so that the damping rate
// b = 2 zeta w_c never passes 1 / h. MuJoCo's Euler applies the damper at the step's
// start velocity, g'_k+1 = (1 - b h) g'_k: with b h > 1 the damper alone reverses an
// approach within one step, and a plastic impact rebounds (measured e = 1.0 for eps = 0 at
// M = 1, where 2 w_c h = 2). So small eps get a softer spring at the same zeta, and eps = 0
// is a pure damper with b = 1 / h, which stops an approach in exactly one Euler step.
ContactParameters calibrated_contact(double eps, double contact_steps, double h);
// MuJoCo 2.2.2's defaults: solref 0.02 1, solimp 0.9 0.95 0.001 0.5 2, margin 0, gap 0.
ContactParameters default_contact();

}  // namespace pb::mujoco
