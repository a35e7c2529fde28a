// Hooke spring with axial damping (forces.h SpringDef for the formula).
#include "rigidlab/debug_draw.h"
#include "rigidlab/error.h"
#include "rigidlab/forces.h"

namespace rigidlab {

SpringForce::SpringForce(const SpringDef& def) : def_(def) {
  requireFinite("local_a", def.local_a);
  requireFinite("local_b", def.local_b);
  requireFinite("anchor", def.anchor);
  requireNonNegative("stiffness", def.stiffness);
  requireNonNegative("damping", def.damping);
  if (!def.rest_length) throw InputError("rest_length", "rest_length must be given");
  requireNonNegative("rest_length", *def.rest_length);
}

void SpringForce::endPoints(const BodyState& a, const BodyState* b, Vec2& pa, Vec2& pb) const {
  pa = a.worldPoint(def_.local_a);
  pb = b ? b->worldPoint(def_.local_b) : def_.anchor;
}

void SpringForce::evaluate(const ForceInput& in, ForceOutput& out) {
  Vec2 pa, pb;
  endPoints(in.a, in.b, pa, pb);
  const Vec2 d = pb - pa;
  const double length = d.norm();
  if (length == 0.0) return;
  const Vec2 u = d / length;
  const Vec2 va = in.a.pointVelocity(pa);
  const Vec2 vb = in.b ? in.b->pointVelocity(pb) : Vec2::Zero();
  // Tension > 0 pulls the ends together: F_a = [k (L − L0) + c (v_b − v_a)·u] u.
  const double tension = def_.stiffness * (length - *def_.rest_length) + def_.damping * (vb - va).dot(u);
  const Vec2 fa = tension * u;
  out.a = atPoint(in.a, fa, pa);
  if (in.b) out.b = atPoint(*in.b, -fa, pb);
}

double SpringForce::potentialEnergy(const BodyState& a, const BodyState* b) const {
  Vec2 pa, pb;
  endPoints(a, b, pa, pb);
  const double x = (pb - pa).norm() - *def_.rest_length;
  return 0.5 * def_.stiffness * x * x;
}

void SpringForce::draw(DebugDraw& dd, const BodyState& a, const BodyState* b) const {
  Vec2 pa, pb;
  endPoints(a, b, pa, pb);
  dd.drawSpring(pa, pb, 0.15, {0.9f, 0.8f, 0.3f, 1.0f});
  if (!b) dd.drawPoint(pb, 5.0f, {0.9f, 0.8f, 0.3f, 1.0f});
}

}  // namespace rigidlab
