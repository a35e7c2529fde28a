// Prismatic joint (a slider): b moves along an axis fixed in a and does not turn relative to it.
// With d the anchors' separation and a the axis turned with A (Box2D v3 prismatic_joint.c):
//   across the axis and the angle, solved together:  C = (p · d, θ),  p = a⊥
//       Ċ = (p · (v_B − v_A) + s₂ ω_B − s₁ ω_A,  ω_B − ω_A),  s₁ = (d + r_A) × p,  s₂ = r_B × p
//       K = [[m_A + m_B + i_A s₁² + i_B s₂², i_A s₁ + i_B s₂], [·, i_A + i_B]]
//   along the axis (spring towards 0, motor, limits on the translation a · d):
//       Ċ = a · (v_B − v_A) + a₂ ω_B − a₁ ω_A,  a₁ = (d + r_A) × a,  a₂ = r_B × a
#include "joint.h"
#include "joint_rows.h"

namespace rigidlab {

void preparePrismatic(Joint& j, const JointStep& step) { j.spring = makeSoft(j.def.spring_hertz, j.def.spring_damping, step.h); }

void solveAxialLimit(SoftBody& a, SoftBody& b, const AxialFrame& f, const JointStep& step, bool use_bias, double c,
                     double sign, double& accumulated) {
  double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
  if (c > 0.0) {
    bias = c * step.inv_h;  // speculative
  } else if (use_bias) {
    bias = step.soft.bias_rate * clampedError(step, c, kMaxLinearCorrection);
    mass_scale = step.soft.mass_scale;
    impulse_scale = step.soft.impulse_scale;
  }
  const double old = accumulated;
  accumulated = std::max(old - mass_scale * f.mass * (sign * f.cdot(a, b) + bias) - impulse_scale * old, 0.0);
  f.apply(a, b, sign * (accumulated - old));
}

AxialFrame axialFrame(const Joint& j, const SoftBody& a, const SoftBody& b) {
  AxialFrame f;
  f.ra = turned(a, j.ra);
  f.rb = turned(b, j.rb);
  f.d = anchorSeparation(j, a, b, f.ra, f.rb);
  f.axis = turned(a, j.axis);
  f.translation = f.axis.dot(f.d);
  f.a1 = cross(f.d + f.ra, f.axis);
  f.a2 = cross(f.rb, f.axis);
  const double k = a.im + b.im + a.ii * f.a1 * f.a1 + b.ii * f.a2 * f.a2;
  f.mass = k > 0.0 ? 1.0 / k : 0.0;
  return f;
}

void solvePrismatic(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias) {
  JointImpulses& p = j.impulses;
  const AxialFrame f = axialFrame(j, a, b);
  if (j.def.enable_spring && j.def.spring_hertz > 0.0 && !step.position) {
    const double impulse =
        -j.spring.mass_scale * f.mass * (f.cdot(a, b) + j.spring.bias_rate * f.translation) - j.spring.impulse_scale * p.spring;
    p.spring += impulse;
    f.apply(a, b, impulse);
  }
  if (j.def.enable_motor && !step.position) {
    const double old = p.motor, max = step.h * j.def.max_motor_force;
    p.motor = std::clamp(old + f.mass * (j.def.motor_speed - f.cdot(a, b)), -max, max);
    f.apply(a, b, p.motor - old);
  }
  if (j.def.enable_limit) {
    solveAxialLimit(a, b, f, step, use_bias, f.translation - j.def.lower, 1.0, p.lower);
    solveAxialLimit(a, b, f, step, use_bias, j.def.upper - f.translation, -1.0, p.upper);
  }
  // Across the axis and the relative angle, as one 2×2 block (joint_rows.cpp).
  solveEqualityRows(j, {&a, &b, &a, &b}, step, use_bias);
}

}  // namespace rigidlab
