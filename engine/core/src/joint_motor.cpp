// Motor joint: drives b's anchor towards a target point fixed in a (linear_offset, in a's frame)
// and b's angle towards angular_offset relative to a, by a spring (motor_hertz, motor_damping; 0
// Hz: the joints' own stiffness) plus a velocity target, with at most max_force and max_torque
// (Box2D 3.2's motor joint; the sandbox drags bodies with one). Friction joint: the same rows with
// no spring and no target: they resist relative motion up to max_force and max_torque (top-down
// friction, Box2D 2.4's b2FrictionJoint). Both are controllers, not constraints: the position pass
// of sequential impulses leaves them alone.
//   angular: Ċ = ω_B − ω_A − ω_target,  λ = −s m (Ċ + β θ) − a P,  |P| ≤ h · max_torque
//   linear:  Ċ = v_B + ω_B × r_B − v_A − ω_A × r_A − v_target, K the point matrix, |P| ≤ h · max_force
#include "joint.h"

namespace rigidlab {

void prepareMotor(Joint& j, const JointStep& step) {
  const double k = j.ia + j.ib;
  j.axial_mass = k > 0.0 ? 1.0 / k : 0.0;
  j.spring = j.def.motor_hertz > 0.0 ? makeSoft(j.def.motor_hertz, j.def.motor_damping, step.h) : step.soft;
}

void solveMotor(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool /*use_bias*/) {
  if (step.position) return;
  JointImpulses& p = j.impulses;
  const bool friction = j.def.type == JointType::Friction;
  const Softness s = friction ? Softness{} : j.spring;
  {
    const double c = friction ? 0.0 : relativeAngle(j, a, b);
    const double cdot = b.w - a.w - (friction ? 0.0 : j.def.angular_velocity);
    const double old = p.angular, max = step.h * j.def.max_torque;
    p.angular = std::clamp(old - s.mass_scale * j.axial_mass * (cdot + s.bias_rate * c) - s.impulse_scale * old, -max, max);
    applyAngular(a, b, p.angular - old);
  }
  const Vec2 ra = turned(a, j.ra), rb = turned(b, j.rb);
  const Vec2 c = friction ? Vec2::Zero() : anchorSeparation(j, a, b, ra, rb);
  const Vec2 target = friction ? Vec2::Zero() : j.def.linear_velocity;
  const Vec2 cdot = pointVelocity(b, rb) - pointVelocity(a, ra) - target;
  const Vec2 x = solvePointMatrix(a, b, ra, rb, cdot + s.bias_rate * c);
  const Vec2 old(p.linear_x, p.linear_y);
  Vec2 total = old - s.mass_scale * x - s.impulse_scale * old;
  const double max = step.h * j.def.max_force;
  if (total.squaredNorm() > max * max) total *= max / total.norm();
  p.linear_x = total.x();
  p.linear_y = total.y();
  applyLinear(a, b, ra, rb, total - old);
}

}  // namespace rigidlab
