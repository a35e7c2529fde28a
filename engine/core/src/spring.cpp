// Hooke spring with axial damping (forces.h SpringDef for the formula).
#include <algorithm>

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

Force::DampingRate SpringForce::dampingRate() const {
  // The damping force c (u·Δv) u at an attachment point r from the body origin resists spin by at
  // most c r² (the origin stands in for the centre of mass: an estimate, good enough for a limit).
  return {def_.damping, def_.damping * def_.local_a.squaredNorm(), def_.damping * def_.local_b.squaredNorm()};
}

bool SpringForce::linearize(const ForceInput& in, ForceJacobian& out) const {
  // At the attachment points: ∂F_a/∂p_a = −K, ∂F_a/∂p_b = K, ∂F_a/∂v_a = −C, ∂F_a/∂v_b = C with
  //   K = k [u uᵀ + max(0, 1 − L0/L) (I − u uᵀ)],   C = c u uᵀ,
  // the transverse term clamped at zero for a compressed spring so the implicit system stays
  // positive definite (Choi & Ko 2002; Baraff & Witkin 1998 for the linearised backward Euler).
  // A point p = c + r moves with the body's coordinates through J = [I | perp(r)], so in
  // generalised coordinates ∂Q_i/∂q_j = J_iᵀ (∂F_i/∂p_j) J_j, and the same for velocities.
  Vec2 pa, pb;
  endPoints(in.a, in.b, pa, pb);
  const Vec2 d = pb - pa;
  const double length = d.norm();
  if (length == 0.0) return true;
  const Vec2 u = d / length;
  const Mat22 uu = u * u.transpose();
  const Mat22 k = def_.stiffness * (uu + std::max(0.0, 1.0 - *def_.rest_length / length) * (Mat22::Identity() - uu));
  const Mat22 c = def_.damping * uu;
  const auto jacobian = [](const Vec2& r) {
    Eigen::Matrix<double, 2, 3> j;
    j << 1.0, 0.0, -r.y(), 0.0, 1.0, r.x();
    return j;
  };
  const Eigen::Matrix<double, 2, 3> ja = jacobian(pa - in.a.center);
  const int n = in.b ? 2 : 1;
  Eigen::Matrix<double, 2, 3> jb;
  if (in.b) jb = jacobian(pb - in.b->center);
  const Eigen::Matrix<double, 2, 3>* js[2] = {&ja, &jb};
  // sign of ∂F_i/∂p_j: −1 on the diagonal, +1 across (F_b = −F_a).
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double sign = i == j ? -1.0 : 1.0;
      out.dq[i][j] = sign * js[i]->transpose() * k * *js[j];
      out.dv[i][j] = sign * js[i]->transpose() * c * *js[j];
    }
  }
  return true;
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
