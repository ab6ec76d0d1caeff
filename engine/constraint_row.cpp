#include "engine/constraint_row.hpp"

namespace rigidlab {

// Box2D v3 b2MakeSoft (E. Catto, "Solver2D" and "Soft Step" notes): the implicit-Euler spring
// of angular frequency ω and damping ratio ζ, expressed as impulse-update coefficients.
Softness make_soft(double hertz, double damping_ratio, double h) {
  if (hertz == 0.0) return rigid_softness;
  const double omega = 2.0 * M_PI * hertz;
  const double a1 = 2.0 * damping_ratio + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return {omega / a1, a2 * a3, a3};
}

}  // namespace rigidlab
