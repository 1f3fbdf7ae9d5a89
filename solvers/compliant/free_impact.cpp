#include "solvers/compliant/free_impact.hpp"

#include <string>

#include "solvers/compliant/compliant.hpp"

namespace pb::compliant {

Result free_impact(std::string_view variant, double eps, double K) {
  System s;
  // w = 1 makes the stiffness unit K m0 w0^2 = K; the body's spring and dashpot are zero.
  s.bodies = {Body{1.0, 1.0, 0.0, 0.0}};
  s.wall = true;
  s.eps = eps;
  s.a_p = 1.0;  // the length unit a_p / w_p^2 = 1 of the Hertz family's stiffness
  s.pulse = Pulse(PulseShape::sine, 0.0, 1.0);
  // A gap of 1e-3 closing at unit speed: the onset at t = 1e-3 is a root CVODE places (a
  // contact that starts closed would be found only at a step's end). The contact lasts pi /
  // sqrt(K) (Kelvin-Voigt) or about 3.2 K^(-2/5) (the Hertz family, at unit speed): 40 time
  // units see it end at every K >= 1 and any eps > 0 (eps = 0 never parts, by design).
  s.u_start = {1e-3};
  s.v_start = {-1.0};
  s.t_end = 40.0;
  s.t_min = 2.0 * std::numbers::pi;
  Settings st;
  st.variant = variant;
  st.stiffness = K;
  st.rtol = 1e-12;
  return solve(s, st);
}

}  // namespace pb::compliant
