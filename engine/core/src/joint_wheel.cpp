// Wheel joint (a car's wheel): b's anchor stays on an axis fixed in a (point on a line, 1 row), a
// suspension spring along the axis, optional translation limits, and a motor on the relative
// rotation; b turns freely otherwise (Box2D v3 wheel_joint.c). Rows as the prismatic joint's
// (joint_prismatic.cpp) without the angle row.
#include "joint.h"
#include "joint_rows.h"

namespace rigidlab {

void prepareWheel(Joint& j, const JointStep& step) {
  const double k = j.ia + j.ib;
  j.axial_mass = k > 0.0 ? 1.0 / k : 0.0;  // the motor's
  j.spring = makeSoft(j.def.spring_hertz, j.def.spring_damping, step.h);
}

void solveWheel(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias) {
  JointImpulses& p = j.impulses;
  const AxialFrame f = axialFrame(j, a, b);
  if (j.def.enable_motor && j.ia + j.ib > 0.0 && !step.position) {
    const double old = p.motor, max = step.h * j.def.max_motor_torque;
    p.motor = std::clamp(old - j.axial_mass * (b.w - a.w - j.def.motor_speed), -max, max);
    applyAngular(a, b, p.motor - old);
  }
  if (j.def.enable_spring && j.def.spring_hertz > 0.0 && !step.position) {
    const double impulse =
        -j.spring.mass_scale * f.mass * (f.cdot(a, b) + j.spring.bias_rate * f.translation) - j.spring.impulse_scale * p.spring;
    p.spring += impulse;
    f.apply(a, b, impulse);
  }
  if (j.def.enable_limit) {
    solveAxialLimit(a, b, f, step, use_bias, f.translation - j.def.lower, 1.0, p.lower);
    solveAxialLimit(a, b, f, step, use_bias, j.def.upper - f.translation, -1.0, p.upper);
  }
  // Point on the line: across the axis, C = a⊥ · d (joint_rows.cpp).
  solveEqualityRows(j, {&a, &b, &a, &b}, step, use_bias);
}

}  // namespace rigidlab
