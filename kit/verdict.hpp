#pragma once
// Whether a run can vouch for its answer. Status ok means only that a run reached t_end with
// finite values; a run can get there without having resolved what it solved (Newmark at N = 64
// with K = 1e4 on the wall, cosine, Pi2 = 1, Pi3 = 0.5: Pi1 8.08 against the answer 1.80,
// restitution 0.38 to 2.29 for eps 0.5, energy made 77 times its scale, and status ok).
// judge() reads the run's own measurements (Result) and says resolved, or unresolved with
// every criterion it failed:
//
//   step         a fixed step longer than a quarter of the shortest period T_min (fewer than
//                kMinStepsPerPeriod steps: w_max h > pi / 2), which resolves neither the bodies'
//                motion nor the pulse's. Moreau-Jean at theta = 1/2 on the stress set: at
//                w_max h = 2 (3.1 steps a period) 95th-percentile Pi1 errors of 45 % to 84 % over
//                its families, at 10 and 100 up to 100 % (every impact missed, Pi1 the ground's
//                own motion), with no other criterion failing there; at 0.5 (12.6 steps) 4 % to
//                16 %. From Result::step, at no cost.
//   contact      a compliant contact shorter than kMinContactSteps steps of the integrator
//                (Result::contact_steps_min), counted in the fixed-step shell's loop at no
//                cost. Newmark's Kelvin-Voigt on the compliant study (K 1e2 to 1e6, N 64 to
//                16384, 576 runs): those whose shortest contact took 4 steps or more erred
//                against the element's exact solution by 0.027 % in the median, 0.75 % at the
//                90th percentile and 6.2 % at most; 2 to 4 steps, 1.1 %, 9 % and 20 %; under 2,
//                9.7 %, 160 % and 1200 %. 4 steps are a half-period at w h = pi / 4, where the
//                trapezoidal rule's period errs by 5 %.
//   energy       energy made beyond kEnergyMade times the energy scale (Result::energy_excess):
//                exact dynamics only lose energy, and a run that made as much as the pulse's
//                whole velocity scale holds (Newmark whose contacts last a step makes 77) did
//                not solve this problem. Below that it is a scheme's order, not a failure: ODE,
//                Bullet and MuJoCo sample the load at a step's start and make O(h) of it (ODE at
//                the default N = 64 on the smoke set: 0.1 to 0.49 on 11 of 40 points, with Pi1
//                errors of 0.05 % to 5.8 %, as on the points where it made less, 0.008 % to
//                7.5 %), which the work-precision study measures. Needs the monitor
//                (Settings::monitor): NaN, so not judged, without it (a work-precision study's
//                runs, and `run` and `spectrum` without --monitor, which solve a point once).
//   restitution  an isolated impact's restitution off eps by more than kRestitutionMargin,
//                where it is measured over one step or event (the monitor's, the reference's):
//                an impact law that does not give eps (Bullet's default variants: 0.42 off in
//                the median; Siconos' Schatzman-Paoli, whose impact spans two steps). Not where
//                it is measured over whole contacts (Result::restitution_over_contacts: the
//                compliant elements, MuJoCo), which carry the model's response to the springs
//                and the load during a contact: a resolved Kelvin-Voigt run at K = 1e2 is 1.2
//                off on slow impacts, and so is the element's exact solution.
//   estimate     a fixed-step run's error estimate (Result::error_estimate) above the target
//                (VerdictScope::target_error, --target-error, default kTargetError = 1 %): the
//                difference between its Pi1 and a companion solve's at twice the step, over
//                2^p - 1 (p = SolverInfo::step_order, 1 for every fixed-step solver), relative to
//                its Pi1. The issue-48 case (wall, cosine, reverse, Pi2 1.0424, Pi3 0.259, eps 0.9,
//                Moreau-Jean at N = 12: Pi1 1.572 against the reference's 0.810) passed every
//                criterion above; its estimate is 43 %. The same test on the fastest impact's
//                approach velocity (Result::error_estimate_velocity; an impact at one step and
//                none at the other is 100 % apart): Pi1 at h and 2h agree by chance where the
//                impacts have not converged (Moreau-Jean on 200 random cases at N = 3 to 16: 18 of
//                291 runs resolved by Pi1's estimate alone were more than 10 % off, 3 of 190 with
//                both). A companion that does not end ok (diverged at 2h) is a doubt (below).
//                What the estimate bounds, and what not: see below.
//   doubt        the solver's own reason it cannot vouch for a run it finished (Result::doubt):
//                the exact Kelvin-Voigt reference above K = 1e12, where a pressed contact's gap
//                nears its state's round-off (its impacts change with --tol-scale).
//
// What the estimate is and is not. It estimates the error of Pi1 at the step h as the
// difference to Pi1 at 2h, assuming Pi1 converges at order p from h on (the asymptotic range):
// it is the leading term of Richardson extrapolation, not a bound. It does not see an error
// that the two steps share (an impact missed at h and at 2h alike, an impact law that is not
// the reference's: Bullet's restitution, the compliant elements' model error against rigid
// contact, which the model's own reference measures), and two steps can agree by chance (the
// companion's error crossing zero near the run's). Pi1 as the largest |u0| over the step ends
// converges at first order where the maximum is non-smooth (at an impact), so p = 1 there;
// where Pi1 converges faster the estimate is high by up to 2^p - 1 (3 for second order): it
// errs toward unresolved. What it measured on random cases (how often a resolved run is still
// more than 10 % off the reference, how often an unresolved one is within 1 %):
// README.md, "How far to trust a run", from scripts/estimate_reliability.py.
//
// A criterion the run did not measure (NaN) is not judged. A run that fails no criterion but
// whose measurements were not all taken (VerdictScope::complete false: a sweep without
// --monitor, or a fixed-step run without --estimate-error) is not judged either: resolved empty,
// never true, since what was not measured could have failed. The reference's own checks turn
// its failures into statuses (penetration, energy), so its ok runs pass; CVODE chooses its own
// steps to its tolerance, so only the monitor's criteria, which it does not measure, could
// fail it. The criteria catch runs that went wrong, not a scheme's order of accuracy: a
// work-precision study measures that against the reference.

#include <string>

#include "cases/system.hpp"
#include "kit/solver.hpp"

namespace pb {

inline constexpr double kMinStepsPerPeriod = 4.0;
inline constexpr double kMinContactSteps = 4.0;
inline constexpr double kEnergyMade = 1.0;
inline constexpr double kRestitutionMargin = 0.1;
inline constexpr double kTargetError = 0.01;

// What a verdict can see besides the Result: the error a resolved run's estimate may reach,
// and whether the run took every measurement it could (false: resolved stays empty unless a
// criterion fails).
struct VerdictScope {
  double target_error = kTargetError;
  bool complete = true;
};

// Sets r.resolved and r.unresolved from r's measurements (a run that did not end ok: empty).
void judge(const System& system, Result& r, const VerdictScope& scope = {});

// A relative error as a percentage with 2 significant digits, "0.83 %" or "94 %".
std::string percent(double relative);

}  // namespace pb
