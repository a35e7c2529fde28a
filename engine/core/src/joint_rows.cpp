// Joints' equality rows (joint_rows.h). Conventions of every row: body a enters with the minus
// sign of "B relative to A", so that for a point constraint Ċ = v_B + ω_B × r_B − v_A − ω_A × r_A
// with ω × r = (−ω r_y, ω r_x):
//   x row:  J_A = (−1, 0,  r_Ay),  J_B = (1, 0, −r_By)
//   y row:  J_A = (0, −1, −r_Ax),  J_B = (0, 1,  r_Bx)
#include "joint_rows.h"

#include <Eigen/Dense>
#include <cmath>

namespace rigidlab {
namespace {

// Row r without a Jacobian yet: its impulse, error and largest correction per position pass.
JointRow& blank(JointRow& r, double* impulse, double error, double max_error) {
  r = JointRow{};
  r.impulse = impulse;
  r.error = error;
  r.max_error = max_error;
  return r;
}

JointRow blank(double* impulse, double error, double max_error) {
  JointRow r;
  return blank(r, impulse, error, max_error);
}

// The two rows of "the anchors coincide" (revolute, weld), written in place (a row copied in
// just after it was made stalls on reading back its fields).
void pointRows(Joint& j, const Vec2& ra, const Vec2& rb, const Vec2& d, RowGroup& g) {
  JointRow& x = blank(g.rows[g.count++], &j.impulses.linear_x, d.x(), kMaxLinearCorrection);
  x.j[0][0] = -1.0;
  x.j[0][2] = ra.y();
  x.j[1][0] = 1.0;
  x.j[1][2] = -rb.y();
  JointRow& y = blank(g.rows[g.count++], &j.impulses.linear_y, d.y(), kMaxLinearCorrection);
  y.j[0][1] = -1.0;
  y.j[0][2] = -ra.x();
  y.j[1][1] = 1.0;
  y.j[1][2] = rb.x();
}

// The relative angle θ_B − θ_A (weld, prismatic).
JointRow angleRow(double* impulse, double angle) {
  JointRow r = blank(impulse, angle, kMaxAngularCorrection);
  r.j[0][2] = -1.0;
  r.j[1][2] = 1.0;
  return r;
}

// Along a direction u through the anchors: Ċ = u · (v_B − v_A) + (r_B' × u) ω_B − (r_A' × u) ω_A,
// with r_A' the lever arm of A's side (prismatic and wheel: d + r_A).
JointRow directionRow(double* impulse, double error, const Vec2& u, const Vec2& lever_a, const Vec2& lever_b) {
  JointRow r = blank(impulse, error, kMaxLinearCorrection);
  r.j[0][0] = -u.x();
  r.j[0][1] = -u.y();
  r.j[0][2] = -cross(lever_a, u);
  r.j[1][0] = u.x();
  r.j[1][1] = u.y();
  r.j[1][2] = cross(lever_b, u);
  return r;
}

double inverseMass(const SoftBody& s, int component) { return component < 2 ? s.im : s.ii; }

}  // namespace

int equalityGroups(Joint& j, const JointBodies& bodies, RowGroup groups[2]) {
  const SoftBody& a = *bodies.a;
  const SoftBody& b = *bodies.b;
  const Vec2 ra = turned(a, j.ra), rb = turned(b, j.rb);
  JointImpulses& p = j.impulses;
  switch (j.def.type) {
    case JointType::Revolute: {
      groups[0] = {};
      pointRows(j, ra, rb, anchorSeparation(j, a, b, ra, rb), groups[0]);
      return 1;
    }
    case JointType::Weld: {
      groups[0] = {};
      groups[0].rows[groups[0].count++] = angleRow(&p.angular, relativeAngle(j, a, b));
      if (j.def.angular_hertz > 0.0) groups[0].spring = &j.angular_soft;
      groups[1] = {};
      pointRows(j, ra, rb, anchorSeparation(j, a, b, ra, rb), groups[1]);
      if (j.def.linear_hertz > 0.0) groups[1].spring = &j.linear_soft;
      return 2;
    }
    case JointType::Prismatic:
    case JointType::Wheel: {
      const Vec2 d = anchorSeparation(j, a, b, ra, rb);
      const Vec2 perp = cross(1.0, turned(a, j.axis));
      groups[0] = {};
      groups[0].rows[groups[0].count++] = directionRow(&p.perpendicular, perp.dot(d), perp, d + ra, rb);
      if (j.def.type == JointType::Prismatic) groups[0].rows[groups[0].count++] = angleRow(&p.angular, relativeAngle(j, a, b));
      return 1;
    }
    case JointType::Distance: {
      // Rigid only: a spring or a range is not an equality (joint_distance.cpp).
      const bool limited = j.def.enable_limit && j.def.min_length < j.def.max_length;
      if ((j.def.enable_spring && j.def.spring_hertz > 0.0) || limited) return 0;
      const Vec2 d = anchorSeparation(j, a, b, ra, rb);
      const double length = d.norm();
      const Vec2 u = length > 1e-12 ? Vec2(d / length) : j.axis;
      const double rest = j.def.enable_limit ? j.def.min_length : j.length;
      groups[0] = {};
      groups[0].rows[groups[0].count++] = directionRow(&p.axial, length - rest, u, ra, rb);
      return 1;
    }
    case JointType::Pulley: {
      const Vec2 pa = j.center_a0 + Vec2(a.dx, a.dy) + ra, pb = j.center_b0 + Vec2(b.dx, b.dy) + rb;
      const Vec2 da = pa - j.def.ground_a, db = pb - j.def.ground_b;
      const double la = da.norm(), lb = db.norm(), r = j.def.ratio;
      const Vec2 ua = la > 1e-9 ? Vec2(da / la) : Vec2::Zero(), ub = lb > 1e-9 ? Vec2(db / lb) : Vec2::Zero();
      JointRow row = blank(&p.axial, la + r * lb - j.length, kMaxLinearCorrection);
      row.j[0][0] = ua.x();
      row.j[0][1] = ua.y();
      row.j[0][2] = cross(ra, ua);
      row.j[1][0] = r * ub.x();
      row.j[1][1] = r * ub.y();
      row.j[1][2] = r * cross(rb, ub);
      groups[0] = {};
      groups[0].rows[groups[0].count++] = row;
      return 1;
    }
    case JointType::Gear: {
      JointRow row = blank(&p.axial, 0.0, kMaxAngularCorrection);
      gearRow(j, bodies, row.j, row.error);
      groups[0] = {};
      groups[0].rows[groups[0].count++] = row;
      return 1;
    }
    case JointType::Motor:
    case JointType::Friction:
      return 0;  // controllers with force limits, not equalities
  }
  return 0;
}

void solveRowGroup(const RowGroup& g, const JointBodies& bodies, const JointStep& step, bool use_bias) {
  SoftBody* body[4] = {bodies.a, bodies.b, bodies.c, bodies.d};
  const int n = g.count;
  // K = J M⁻¹ Jᵀ; rows that move nothing (every body immovable along them) are left out.
  Eigen::Matrix3d k = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      for (int b = 0; b < 4; ++b)
        for (int q = 0; q < 3; ++q) k(r, c) += g.rows[r].j[b][q] * inverseMass(*body[b], q) * g.rows[c].j[b][q];
  const Softness& soft = g.spring ? *g.spring : step.soft;
  const bool biased = g.spring ? !step.position : use_bias;  // a spring acts in the relax pass too
  const double mass_scale = biased ? soft.mass_scale : 1.0, impulse_scale = biased ? soft.impulse_scale : 0.0;
  for (int r = 0; r < n; ++r) {
    const JointRow& row = g.rows[r];
    double cdot = 0.0;
    for (int b = 0; b < 4; ++b)
      cdot += row.j[b][0] * body[b]->vx + row.j[b][1] * body[b]->vy + row.j[b][2] * body[b]->w;
    const double error = step.position ? std::clamp(row.error, -row.max_error, row.max_error) : row.error;
    rhs(r) = cdot + (biased ? soft.bias_rate * error : 0.0);
  }
  bool free[3] = {false, false, false};
  for (int r = 0; r < n; ++r)
    if (!(k(r, r) > 0.0)) {
      free[r] = true;
      k.row(r).setZero();
      k.col(r).setZero();
      k(r, r) = 1.0;
      rhs(r) = 0.0;
    }
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  if (n == 1) {
    x(0) = rhs(0) / k(0, 0);
  } else {
    x.head(n) = k.topLeftCorner(n, n).ldlt().solve(rhs.head(n));
  }
  for (int r = 0; r < n; ++r) {
    if (free[r]) continue;
    const JointRow& row = g.rows[r];
    const double impulse = -mass_scale * x(r) - impulse_scale * *row.impulse;
    *row.impulse += impulse;
    for (int b = 0; b < 4; ++b) {
      body[b]->vx += body[b]->im * impulse * row.j[b][0];
      body[b]->vy += body[b]->im * impulse * row.j[b][1];
      body[b]->w += body[b]->ii * impulse * row.j[b][2];
    }
  }
}

void warmStartRows(Joint& j, const JointBodies& bodies) {
  SoftBody* body[4] = {bodies.a, bodies.b, bodies.c, bodies.d};
  RowGroup groups[2];
  const int count = equalityGroups(j, bodies, groups);
  for (int i = 0; i < count; ++i)
    for (int r = 0; r < groups[i].count; ++r) {
      const JointRow& row = groups[i].rows[r];
      for (int b = 0; b < 4; ++b) {
        body[b]->vx += body[b]->im * *row.impulse * row.j[b][0];
        body[b]->vy += body[b]->im * *row.impulse * row.j[b][1];
        body[b]->w += body[b]->ii * *row.impulse * row.j[b][2];
      }
    }
}

void solveEqualityRows(Joint& j, const JointBodies& bodies, const JointStep& step, bool use_bias) {
  RowGroup groups[2];
  const int count = equalityGroups(j, bodies, groups);
  for (int i = 0; i < count; ++i) {
    if (step.position && groups[i].spring) continue;  // springs are not errors
    // Each group from the rows at the current state: the first group moved the bodies.
    if (i > 0) {
      RowGroup again[2];
      equalityGroups(j, bodies, again);
      solveRowGroup(again[i], bodies, step, use_bias);
    } else {
      solveRowGroup(groups[i], bodies, step, use_bias);
    }
  }
}

}  // namespace rigidlab
