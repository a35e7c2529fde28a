// The cursor drag force: a damped spring to the cursor with a capped magnitude (forces.h).
#include <numbers>

#include "rigidlab/debug_draw.h"
#include "rigidlab/error.h"
#include "rigidlab/forces.h"

namespace rigidlab {

MouseForce::MouseForce(const MouseForceDef& def) : def_(def) {
  requireFinite("local_point", def.local_point);
  requireFinite("target", def.target);
  requireNonNegative("stiffness", def.stiffness);
  requireNonNegative("damping", def.damping);
  requirePositive("max_force", def.max_force);
}

void MouseForce::evaluate(const ForceInput& in, ForceOutput& out) {
  const Vec2 p = in.a.worldPoint(def_.local_point);
  Vec2 f = def_.stiffness * (def_.target - p) - def_.damping * in.a.pointVelocity(p);
  const double magnitude = f.norm();
  if (magnitude > def_.max_force) f *= def_.max_force / magnitude;
  out.a = atPoint(in.a, f, p);
}

void MouseForce::draw(DebugDraw& dd, const BodyState& a, const BodyState*) const {
  const Vec2 p = a.worldPoint(def_.local_point);
  const Color c{0.3f, 0.9f, 0.4f, 1.0f};
  dd.drawSegment(p, def_.target, c);
  dd.drawPoint(p, 6.0f, c);
  dd.drawPoint(def_.target, 6.0f, c);
}

MouseForceDef MouseForce::forBody(const Body& body, const Vec2& grab_point, double hertz, double zeta,
                                  double max_accel) {
  // Spring–damper of natural frequency ω = 2π·hertz on the body's mass: k = m ω², c = 2 m ζ ω.
  const double omega = 2.0 * std::numbers::pi * hertz;
  MouseForceDef def;
  def.body = body.id;
  def.local_point = body.xf.applyInverse(grab_point);
  def.target = grab_point;
  def.stiffness = body.mass * omega * omega;
  def.damping = 2.0 * body.mass * zeta * omega;
  def.max_force = max_accel * body.mass;
  return def;
}

}  // namespace rigidlab
