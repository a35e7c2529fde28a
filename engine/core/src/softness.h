// Soft constraints (E. Catto, "Soft Step", GDC 2011; "Solver2D", 2024): a constraint behaves like a
// spring of frequency f and damping ratio ζ integrated implicitly over the step h. With ω = 2πf,
//   a₁ = 2ζ + hω,  a₂ = hω a₁,  a₃ = 1/(1 + a₂)
// the velocity impulse of a constraint with position error C and velocity error Ċ is
//   λ = −m (a₂a₃ (Ċ + β C)) − a₃ P,   β = ω/a₁ (bias rate), P the accumulated impulse,
// i.e. mass scale a₂a₃ and impulse scale a₃. Hertz 0 is the rigid constraint: no bias, mass scale 1.
#pragma once

#include <cmath>

namespace rigidlab {

struct Softness {
  double bias_rate = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
};

inline Softness makeSoft(double hertz, double zeta, double h) {
  if (hertz == 0.0) return {0.0, 1.0, 0.0};
  const double omega = 2.0 * M_PI * hertz;
  const double a1 = 2.0 * zeta + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return {omega / a1, a2 * a3, a3};
}

}  // namespace rigidlab
