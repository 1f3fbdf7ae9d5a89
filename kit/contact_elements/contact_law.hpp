#pragma once
// The compliant contact elements of earthquake engineering practice: a force that acts
// between two neighbours (or a body and the wall) only while their gap is closed, as a
// function of the penetration p = -g > 0 and its rate q = p' (> 0 while approaching).
//
//   kelvin-voigt   F = k p + c q, c = 2 zeta sqrt(k m_eff)          (Anagnostopoulos 1988)
//                  zeta = -ln(eps) / sqrt(pi^2 + ln(eps)^2)
//   hertz          F = k p^(3/2)                                     elastic: eps = 1 only
//   hunt-crossley  F = max(0, k p^(3/2) (1 + chi q / v-))            (Hertzdamp, Muthukumar
//                  v- the approach rate at the contact's onset         & DesRoches 2006)
//   jankowski      F = k p^(3/2) + c q while q > 0, k p^(3/2) after,  (Jankowski 2005)
//                  c = 2 zeta_J sqrt(k sqrt(p) m_eff), zeta_J calibrated to eps
//   jankowski-published  the same element with Jankowski's own closed form,
//                  zeta_J = 9 sqrt(5) (1 - eps^2) / (2 eps (eps (9 pi - 16) + 16)),
//                  which practitioners use: it restitutes less than eps (0.2917 at 0.3)
//
// m_eff = m_L m_R / (m_L + m_R), or m_R against the wall.
//
// End condition: every element acts while p > 0 and ends when the penetration does. The
// Kelvin-Voigt force is not clamped: near the end of a contact its dashpot pulls (c q < 0
// with k p small), and with it the textbook zeta restitutes exactly eps (the contact is a
// damped half-oscillation). Clamping that force at zero would end the push early and
// return more velocity, so the clamped element needs a larger zeta for the same eps (the
// clamped linear oscillator of Schwager & Poeschel: 0.2553 instead of 0.2155 at eps = 0.5).
// At eps = 0 the Kelvin-Voigt element is critically damped and its penetration never ends
// by itself: it holds the bodies together until the other forces part them.
// The Hunt-Crossley force is clamped: with chi > 1 its damping would otherwise pull.
//
// Stiffness as a Pi term K (cases/README.md): k = K m0 w0^2 for the linear element, and
// k = K m0 w0^2 / sqrt(L) for the Hertz family, so that at a penetration of L every element
// pushes K times body 0's own spring force at that displacement. L = a_p / w_p^2 for the
// paper's pulses and the pulse models, and Pi1 depends on dimensionless groups only; for a
// record, whose a_p and w_p are only a unit, L is the record's own (its peak over its mean
// circular frequency squared), so that the model does not move with that unit.
//
// chi of Hunt-Crossley: the isolated impact of that element is scale-free (in units of
// X = (m_eff v-^2 / k)^(2/5) and X / v- it is x'' = -x^(3/2) (1 + chi x'), x(0) = 0,
// x'(0) = 1), so its restitution depends on chi alone; hunt_crossley_chi(eps) finds the chi
// that restitutes eps by bisection on that integral, once per eps (cached). The published
// closed forms, Lankarani-Nikravesh 3 (1 - eps^2) / 4 and Flores 8 (1 - eps) / (5 eps), are
// kept for the report, with the restitution each actually gives (hunt_crossley_restitution).
// Jankowski's zeta_J the same way: in those units his isolated impact is
// x'' = -x^(3/2) - 2 zeta_J x^(1/4) x' while x' > 0, and elastic after, so it restitutes
// sqrt(4/5 x_max^(5/2)) from its deepest point; jankowski_zeta(eps) bisects on that.

#include <array>
#include <optional>
#include <string_view>

namespace pb::compliant {

enum class Model { kelvin_voigt, hertz, hunt_crossley, jankowski, jankowski_published };
inline constexpr std::array kModels = {Model::kelvin_voigt, Model::hertz, Model::hunt_crossley, Model::jankowski,
                                       Model::jankowski_published};

std::string_view name(Model m);
std::string_view summary(Model m);  // one line, for `poundbench solvers`
std::optional<Model> parse_model(std::string_view text);  // "" is kelvin-voigt

// Why a model cannot restitute eps ("" when it can).
std::string_view eps_problem(Model m, double eps);

// The default Pi term K: stiff enough that the Kelvin-Voigt model's Pi1 is within ~1e-3 of
// the rigid answer on the paper's cases, and still resolvable by CVODE in milliseconds.
inline constexpr double kDefaultStiffness = 1e4;

// One contact's element, set up once per run.
struct Law {
  Model model = Model::kelvin_voigt;
  double k = 0.0;     // stiffness (N/m, or N/m^(3/2) for the Hertz family)
  double c = 0.0;     // kelvin-voigt: the dashpot
  double chi = 0.0;   // hunt-crossley
  double zeta = 0.0;  // the jankowski elements: zeta_J; kelvin-voigt: zeta
  double m_eff = 0.0;

  // The force at penetration p > 0 and rate q, for a contact that began approaching at v_minus.
  double force(double p, double q, double v_minus) const;
  // Its derivatives by p and by q (Newton's method in the Newmark integrator).
  void slopes(double p, double q, double v_minus, double& dp, double& dq) const;
};

// The element of a contact between masses m_left (0: the wall) and m_right, for eps and k.
Law make_law(Model model, double k, double eps, double m_left, double m_right);

// Kelvin-Voigt's damping ratio for eps (the unclamped element: exact).
double kelvin_voigt_zeta(double eps);
// Jankowski's damping ratio that makes his element's isolated impact restitute eps
// (0 < eps <= 1), and his own closed-form approximation of it.
double jankowski_zeta(double eps);
double jankowski_published_zeta(double eps);
// The restitution of an isolated impact of his element with that zeta_J.
double jankowski_restitution(double zeta);
// chi that makes an isolated Hunt-Crossley impact restitute eps (0 < eps <= 1).
double hunt_crossley_chi(double eps);
// The restitution of an isolated Hunt-Crossley impact with that chi.
double hunt_crossley_restitution(double chi);
// The published closed forms of chi.
double lankarani_nikravesh_chi(double eps);
double flores_chi(double eps);

}  // namespace pb::compliant
