// What every joint shares (joint.h): preparing the frames, scaling carried impulses, dispatching to
// the type, the reaction force.
#include "joint.h"

#include <cmath>

namespace rigidlab {

const char* jointTypeName(JointType t) {
  switch (t) {
    case JointType::Revolute: return "revolute";
    case JointType::Prismatic: return "prismatic";
    case JointType::Distance: return "distance";
    case JointType::Weld: return "weld";
    case JointType::Wheel: return "wheel";
    case JointType::Motor: return "motor";
    case JointType::Friction: return "friction";
    case JointType::Pulley: return "pulley";
    case JointType::Gear: return "gear";
  }
  return "?";
}

void solvePointConstraint(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias) {
  const Vec2 ra = turned(a, j.ra), rb = turned(b, j.rb);
  const Softness& soft = step.soft;
  const double mass_scale = use_bias ? soft.mass_scale : 1.0, impulse_scale = use_bias ? soft.impulse_scale : 0.0;
  Vec2 c = anchorSeparation(j, a, b, ra, rb);
  if (step.position)  // each row's error clamped on its own, as the rows of joint_rows.cpp are
    c = Vec2(std::clamp(c.x(), -kMaxLinearCorrection, kMaxLinearCorrection),
             std::clamp(c.y(), -kMaxLinearCorrection, kMaxLinearCorrection));
  const Vec2 cdot = pointVelocity(b, rb) - pointVelocity(a, ra);
  const Vec2 x = solvePointMatrix(a, b, ra, rb, use_bias ? Vec2(cdot + soft.bias_rate * c) : cdot);
  JointImpulses& p = j.impulses;
  const Vec2 impulse = -mass_scale * x - impulse_scale * Vec2(p.linear_x, p.linear_y);
  p.linear_x += impulse.x();
  p.linear_y += impulse.y();
  applyLinear(a, b, ra, rb, impulse);
}

void prepareJoint(Joint& j, const JointBodyPose& a, const JointBodyPose& b, const JointBodyPose* c,
                  const JointBodyPose* d, const JointStep& step) {
  j.type = j.def.type;
  j.enable_limit = j.def.enable_limit;
  j.enable_motor = j.def.enable_motor;
  j.enable_spring = j.def.enable_spring && j.def.spring_hertz > 0.0;
  j.lower = j.def.lower;
  j.upper = j.def.upper;
  j.motor_speed = j.def.motor_speed;
  j.max_motor_torque = j.def.max_motor_torque;
  j.ma = a.inv_mass;
  j.ia = a.inv_inertia;
  j.mb = b.inv_mass;
  j.ib = b.inv_inertia;
  // Anchors from the centres in world rotation: r = q (p_local − c_local).
  j.ra = a.q.apply(j.local_a - a.local_center);
  j.rb = b.q.apply(j.local_b - b.local_center);
  j.delta_center = b.center - a.center;
  j.delta_angle = b.angle - a.angle - j.reference_angle;
  j.axis = a.q.apply(j.local_axis);
  j.center_a0 = a.center;
  j.angle_a0 = a.angle;
  j.center_b0 = b.center;
  j.angle_b0 = b.angle;
  if (c && d) {
    j.mc = c->inv_mass;
    j.ic = c->inv_inertia;
    j.md = d->inv_mass;
    j.id = d->inv_inertia;
    j.center_c0 = c->center;
    j.angle_c0 = c->angle;
    j.center_d0 = d->center;
    j.angle_d0 = d->angle;
  }
  // Impulses carried over are those of a step (or sub-step) of length impulse_h: for the same
  // forces, an impulse scales with the time it acts over.
  if (!step.warm_starting) {
    j.impulses = {};
  } else if (j.impulse_h > 0.0 && j.impulse_h != step.h) {
    const double s = step.h / j.impulse_h;
    JointImpulses& p = j.impulses;
    for (double* x : {&p.linear_x, &p.linear_y, &p.angular, &p.perpendicular, &p.axial, &p.spring, &p.motor, &p.lower,
                      &p.upper, &p.spring_x, &p.spring_y})
      *x *= s;
  }
  j.impulse_h = step.h;
  switch (j.def.type) {
    case JointType::Revolute: prepareRevolute(j, step); break;
    case JointType::Distance: prepareDistance(j, step); break;
    case JointType::Prismatic: preparePrismatic(j, step); break;
    case JointType::Wheel: prepareWheel(j, step); break;
    case JointType::Weld: prepareWeld(j, step); break;
    case JointType::Motor:
    case JointType::Friction: prepareMotor(j, step); break;
    case JointType::Pulley: preparePulley(j, step); break;
    case JointType::Gear: prepareGear(j, a, b, *c, *d); break;
  }
}

void warmStartJoint(Joint& j, const JointBodies& bodies) {
  SoftBody& a = *bodies.a;
  SoftBody& b = *bodies.b;
  const JointImpulses& p = j.impulses;
  const Vec2 ra = turned(a, j.ra), rb = turned(b, j.rb);
  switch (j.type) {
    case JointType::Revolute:
      applyLinear(a, b, ra, rb, Vec2(p.linear_x, p.linear_y));
      applyAngular(a, b, p.spring + p.motor + p.lower - p.upper);
      break;
    case JointType::Weld:
    case JointType::Motor:
    case JointType::Friction:
      applyLinear(a, b, ra, rb, Vec2(p.linear_x + p.spring_x, p.linear_y + p.spring_y));
      applyAngular(a, b, p.angular + p.spring);
      break;
    case JointType::Prismatic:
    case JointType::Wheel: {
      // Along the axis and across it, with the torques their lever arms give (a₁, a₂, s₁, s₂).
      const Vec2 dvec = anchorSeparation(j, a, b, ra, rb);
      const Vec2 axis = turned(a, j.axis), perp = cross(1.0, axis);
      const double axial = j.def.type == JointType::Prismatic ? p.spring + p.motor + p.lower - p.upper
                                                               : p.spring + p.lower - p.upper;
      const double angular = j.def.type == JointType::Prismatic ? p.angular : p.motor;
      const Vec2 P = axial * axis + p.perpendicular * perp;
      const double la = axial * cross(dvec + ra, axis) + p.perpendicular * cross(dvec + ra, perp) + angular;
      const double lb = axial * cross(rb, axis) + p.perpendicular * cross(rb, perp) + angular;
      a.vx -= a.im * P.x();
      a.vy -= a.im * P.y();
      a.w -= a.ii * la;
      b.vx += b.im * P.x();
      b.vy += b.im * P.y();
      b.w += b.ii * lb;
      break;
    }
    case JointType::Distance: {
      const Vec2 dvec = anchorSeparation(j, a, b, ra, rb);
      const double len = dvec.norm();
      const Vec2 u = len > 1e-12 ? Vec2(dvec / len) : j.axis;
      applyLinear(a, b, ra, rb, (p.axial + p.lower - p.upper + p.motor) * u);
      break;
    }
    case JointType::Pulley: warmStartPulley(j, a, b); break;
    case JointType::Gear: warmStartGear(j, bodies); break;
  }
}

void solveJoint(Joint& j, const JointBodies& bodies, const JointStep& step, bool use_bias) {
  SoftBody& a = *bodies.a;
  SoftBody& b = *bodies.b;
  switch (j.type) {
    case JointType::Revolute: solveRevolute(j, a, b, step, use_bias); break;
    case JointType::Distance: solveDistance(j, a, b, step, use_bias); break;
    case JointType::Prismatic: solvePrismatic(j, a, b, step, use_bias); break;
    case JointType::Wheel: solveWheel(j, a, b, step, use_bias); break;
    case JointType::Weld: solveWeld(j, a, b, step, use_bias); break;
    case JointType::Motor:
    case JointType::Friction: solveMotor(j, a, b, step, use_bias); break;
    case JointType::Pulley: solvePulley(j, a, b, step, use_bias); break;
    case JointType::Gear: solveGear(j, bodies, step, use_bias); break;
  }
}

void jointReaction(const Joint& j, Vec2& force, double& torque) {
  force = Vec2::Zero();
  torque = 0.0;
  if (!(j.impulse_h > 0.0)) return;
  const JointImpulses& p = j.impulses;
  const double inv_h = 1.0 / j.impulse_h;
  const Vec2 perp = cross(1.0, j.axis);
  switch (j.def.type) {
    case JointType::Revolute:
      force = Vec2(p.linear_x, p.linear_y);
      torque = p.spring + p.motor + p.lower - p.upper;
      break;
    case JointType::Weld:
    case JointType::Motor:
    case JointType::Friction:
      force = Vec2(p.linear_x + p.spring_x, p.linear_y + p.spring_y);
      torque = p.angular + p.spring;
      break;
    case JointType::Prismatic:
      force = (p.spring + p.motor + p.lower - p.upper) * j.axis + p.perpendicular * perp;
      torque = p.angular;
      break;
    case JointType::Wheel:
      force = (p.spring + p.lower - p.upper) * j.axis + p.perpendicular * perp;
      torque = p.motor;
      break;
    case JointType::Distance:
      force = (p.axial + p.lower - p.upper + p.motor) * j.axis;
      break;
    case JointType::Pulley:
      force = j.def.ratio * p.axial * j.axis;  // j.axis holds b's rope direction (joint_pulley.cpp)
      break;
    case JointType::Gear:
      torque = j.def.ratio * p.axial;
      break;
  }
  force *= inv_h;
  torque *= inv_h;
}

}  // namespace rigidlab
