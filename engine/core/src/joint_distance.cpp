// Distance joint: the anchors keep their distance L = |d| (rigid: C = L − length), or stay within
// [min_length, max_length] (a rope is max_length alone), or are held by a spring towards `length`
// whose force is at most max_spring_force (Box2D v3 distance_joint.c). Along u = d/|d|:
//   Ċ = u · (v_B + ω_B × r_B − v_A − ω_A × r_A),  k = 1/(m_A + m_B + i_A (r_A × u)² + i_B (r_B × u)²)
#include "joint.h"
#include "joint_rows.h"

namespace rigidlab {

void prepareDistance(Joint& j, const JointStep& step) {
  const Vec2 d = j.delta_center + j.rb - j.ra;
  const double len = d.norm();
  j.axis = len > 1e-12 ? Vec2(d / len) : Vec2(1.0, 0.0);
  const double cra = cross(j.ra, j.axis), crb = cross(j.rb, j.axis);
  const double k = j.ma + j.mb + j.ia * cra * cra + j.ib * crb * crb;
  j.axial_mass = k > 0.0 ? 1.0 / k : 0.0;
  j.spring = makeSoft(j.def.spring_hertz, j.def.spring_damping, step.h);
}

void solveDistance(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias) {
  JointImpulses& p = j.impulses;
  const Vec2 ra = turned(a, j.ra), rb = turned(b, j.rb);
  const Vec2 d = anchorSeparation(j, a, b, ra, rb);
  const double length = d.norm();
  const Vec2 u = length > 1e-12 ? Vec2(d / length) : j.axis;
  const double cra = cross(ra, u), crb = cross(rb, u);
  const double kk = j.ma + j.mb + j.ia * cra * cra + j.ib * crb * crb;
  const double mass = kk > 0.0 ? 1.0 / kk : 0.0;
  const auto cdot = [&] { return u.dot(pointVelocity(b, rb) - pointVelocity(a, ra)); };
  const bool limited = j.def.enable_limit && j.def.min_length < j.def.max_length;
  const bool spring = j.def.enable_spring && j.def.spring_hertz > 0.0;
  if (!spring && !limited) {  // rigid at the rest length (or at min_length = max_length): joint_rows.cpp
    solveEqualityRows(j, {&a, &b, &a, &b}, step, use_bias);
    return;
  }
  if (spring && !step.position) {  // a real spring: in the relax pass too, never in the position pass
    const double old = p.axial;
    const double impulse = -j.spring.mass_scale * mass * (cdot() + j.spring.bias_rate * (length - j.length)) -
                           j.spring.impulse_scale * old;
    const double max = step.h * j.def.max_spring_force;
    p.axial = std::clamp(old + impulse, -max, max);
    applyLinear(a, b, ra, rb, (p.axial - old) * u);
  }
  if (!limited) return;
  // The range: min_length ≤ L ≤ max_length, one-sided rows as for the revolute joint's limits.
  const auto limit = [&](double c, double sign, double& accumulated) {
    double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
    if (c > 0.0) {
      bias = c * step.inv_h;
    } else if (use_bias) {
      bias = step.soft.bias_rate * clampedError(step, c, kMaxLinearCorrection);
      mass_scale = step.soft.mass_scale;
      impulse_scale = step.soft.impulse_scale;
    }
    const double old = accumulated;
    accumulated = std::max(old - mass_scale * mass * (sign * cdot() + bias) - impulse_scale * old, 0.0);
    applyLinear(a, b, ra, rb, (sign * (accumulated - old)) * u);
  };
  limit(length - j.def.min_length, 1.0, p.lower);
  if (std::isfinite(j.def.max_length)) limit(j.def.max_length - length, -1.0, p.upper);
}

}  // namespace rigidlab
