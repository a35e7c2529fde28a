// Revolute joint (a pin): the anchors coincide, C = d = 0 (2 rows); optional rotational spring,
// motor and angle limits on θ = θ_B − θ_A − θ_ref (1 row each), solved in that order so that the
// point constraint has the last word (Box2D v3 revolute_joint.c).
//
//   point:   Ċ = v_B + ω_B × r_B − v_A − ω_A × r_A,  K = the 2×2 point matrix (joint.h)
//   angular: Ċ = ω_B − ω_A,  k = 1/(i_A + i_B) ("axial mass")
//   spring:  soft with the spring's own hertz and damping (also in the relax pass: it is a real
//            spring, not an error correction)
//   motor:   Ċ = ω_B − ω_A − speed, impulse clamped to ±h · max torque
//   limits:  lower C = θ − lower ≥ 0, upper C = upper − θ ≥ 0, impulses ≥ 0; a limit not yet
//            reached may close by C in this step (speculative: bias C/h), a violated one is pushed
//            back by the soft bias.
#include "joint.h"

namespace rigidlab {

void prepareRevolute(Joint& j, const JointStep& step) {
  const double k = j.ia + j.ib;
  j.axial_mass = k > 0.0 ? 1.0 / k : 0.0;
  j.spring = makeSoft(j.def.spring_hertz, j.def.spring_damping, step.h);
}

namespace {

// One limit row: C ≥ 0 with Ċ = sign (ω_B − ω_A), accumulated impulse ≥ 0.
void solveAngularLimit(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias, double c, double sign,
                       double& accumulated) {
  double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
  if (c > 0.0) {
    bias = c * step.inv_h;  // speculative: may close this much in this step
  } else if (use_bias) {
    bias = step.soft.bias_rate * clampedError(step, c, kMaxAngularCorrection);
    mass_scale = step.soft.mass_scale;
    impulse_scale = step.soft.impulse_scale;
  }
  const double cdot = sign * (b.w - a.w);
  const double old = accumulated;
  accumulated = std::max(old - mass_scale * j.axial_mass * (cdot + bias) - impulse_scale * old, 0.0);
  applyAngular(a, b, sign * (accumulated - old));
}

}  // namespace

void solveRevolute(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias) {
  JointImpulses& p = j.impulses;
  const bool turns = j.ia + j.ib > 0.0;
  const bool spring = j.enable_spring && turns && !step.position, limit = j.enable_limit && turns;
  // θ once: the spring, motor and limits change the bodies' angular velocities, not their rotations.
  const double angle = spring || limit ? relativeAngle(j, a, b) : 0.0;
  if (spring) {
    const double impulse = -j.spring.mass_scale * j.axial_mass * (b.w - a.w + j.spring.bias_rate * angle) -
                           j.spring.impulse_scale * p.spring;
    p.spring += impulse;
    applyAngular(a, b, impulse);
  }
  if (j.enable_motor && turns && !step.position) {
    const double old = p.motor, max = step.h * j.max_motor_torque;
    p.motor = std::clamp(old - j.axial_mass * (b.w - a.w - j.motor_speed), -max, max);
    applyAngular(a, b, p.motor - old);
  }
  if (limit) {
    solveAngularLimit(j, a, b, step, use_bias, angle - j.lower, 1.0, p.lower);
    solveAngularLimit(j, a, b, step, use_bias, j.upper - angle, -1.0, p.upper);
  }
  solvePointConstraint(j, a, b, step, use_bias);
}

}  // namespace rigidlab
