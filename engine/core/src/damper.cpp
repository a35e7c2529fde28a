// Linear and angular damper, F = −c v and τ = −c_ω ω (docs/design/thesis.md §1, §4).
#include "rigidlab/debug_draw.h"
#include "rigidlab/error.h"
#include "rigidlab/forces.h"

namespace rigidlab {

DamperForce::DamperForce(const DamperDef& def) : def_(def) {
  requireNonNegative("coefficient", def.coefficient);
  requireNonNegative("angular_coefficient", def.angular_coefficient);
}

void DamperForce::evaluate(const ForceInput& in, ForceOutput& out) {
  out.a.force = -def_.coefficient * in.a.velocity;
  out.a.torque = -def_.angular_coefficient * in.a.angular_velocity;
}

bool DamperForce::linearize(const ForceInput&, ForceJacobian& out) const {
  out.dv[0][0].diagonal() << -def_.coefficient, -def_.coefficient, -def_.angular_coefficient;
  return true;
}

void DamperForce::draw(DebugDraw& dd, const BodyState& a, const BodyState*) const {
  // A small dashpot glyph on the centre of mass: a cylinder (two rails) and a piston rod.
  const Color c{0.5f, 0.8f, 0.9f, 1.0f};
  const Vec2 x = a.q.apply(Vec2(0.12, 0.0)), y = a.q.apply(Vec2(0.0, 0.06));
  dd.drawSegment(a.center - x + y, a.center + x + y, c);
  dd.drawSegment(a.center - x - y, a.center + x - y, c);
  dd.drawSegment(a.center - 1.6 * x, a.center + 0.4 * x, c);
}

}  // namespace rigidlab
