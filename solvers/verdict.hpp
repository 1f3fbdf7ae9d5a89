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
//   doubt        the solver's own reason it cannot vouch for a run it finished (Result::doubt):
//                the exact Kelvin-Voigt reference above K = 1e12, where a pressed contact's gap
//                nears its state's round-off (its impacts change with --tol-scale).
//
// A criterion the run did not measure (NaN) is not judged. The reference's own checks turn
// its failures into statuses (penetration, energy), so its ok runs pass; CVODE chooses its own
// steps to its tolerance, so only the monitor's criteria, which it does not measure, could
// fail it. The criteria catch runs that went wrong, not a scheme's order of accuracy: a
// work-precision study measures that against the reference.

#include <string>

#include "cases/system.hpp"
#include "solvers/solver.hpp"

namespace pb {

inline constexpr double kMinStepsPerPeriod = 4.0;
inline constexpr double kMinContactSteps = 4.0;
inline constexpr double kEnergyMade = 1.0;
inline constexpr double kRestitutionMargin = 0.1;

// Sets r.resolved and r.unresolved from r's measurements (a run that did not end ok: empty).
void judge(const System& system, Result& r);

}  // namespace pb
