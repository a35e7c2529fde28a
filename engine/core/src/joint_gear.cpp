// Gear joint: couples two revolute or prismatic joints so that coordinate_1 + ratio · coordinate_2
// stays as it was (Box2D 2.4 b2GearJoint). Joint 1 joins C (its a) and A (its b), joint 2 joins D
// and B; a coordinate is an angle θ_A − θ_C − θ_ref or a translation u · (p_A − p_C) along the
// axis u fixed in C. One row over four bodies:
//   revolute:  J_A = (0, 1), J_C = (0, 1)              (the C terms enter with a minus sign)
//   prismatic: J_A = (u, r_A × u), J_C = (u, r_C × u)  (r_C from C's centre to its anchor, r_A to A's)
//   Ċ = J_A · ẋ_A − J_C · ẋ_C + ratio (J_B · ẋ_B − J_D · ẋ_D)
#include "rigidlab/portable_math.h"
#include "joint.h"
#include "joint_rows.h"

namespace rigidlab {
namespace {

struct GearRow {
  Vec2 jv[2];           // linear parts (zero on a revolute side)
  double jw_x[2], jw_g[2];
  double coordinate = 0.0;  // coordinate_1 + ratio · coordinate_2
};

GearRow row(const Joint& j, const JointBodies& bodies) {
  GearRow r;
  for (int s = 0; s < 2; ++s) {
    const Joint::GearSide& side = j.gear[s];
    const SoftBody& x = s == 0 ? *bodies.a : *bodies.b;
    const SoftBody& g = s == 0 ? *bodies.c : *bodies.d;
    const double scale = s == 0 ? 1.0 : j.def.ratio;
    double coordinate;
    if (side.revolute) {
      r.jv[s] = Vec2::Zero();
      r.jw_x[s] = r.jw_g[s] = scale;
      // θ_X − θ_G − θ_ref: at prepare, plus the relative rotation since.
      const double ax0 = s == 0 ? j.angle_a0 : j.angle_b0, ag0 = s == 0 ? j.angle_c0 : j.angle_d0;
      coordinate = ax0 - ag0 - side.reference + portableAtan2(g.qc * x.qs - g.qs * x.qc, g.qc * x.qc + g.qs * x.qs);
    } else {
      const Vec2 u = turned(g, side.u), rg = turned(g, side.rg), rx = turned(x, side.rx);
      r.jv[s] = scale * u;
      r.jw_g[s] = scale * cross(rg, u);
      r.jw_x[s] = scale * cross(rx, u);
      const Vec2 cx0 = s == 0 ? j.center_a0 : j.center_b0, cg0 = s == 0 ? j.center_c0 : j.center_d0;
      coordinate = u.dot((cx0 + Vec2(x.dx, x.dy) + rx) - (cg0 + Vec2(g.dx, g.dy) + rg));
    }
    r.coordinate += scale * coordinate;
  }
  return r;
}

}  // namespace

void prepareGear(Joint& j, const JointBodyPose& a, const JointBodyPose& b, const JointBodyPose& c, const JointBodyPose& d) {
  for (int s = 0; s < 2; ++s) {
    Joint::GearSide& side = j.gear[s];
    const JointBodyPose& x = s == 0 ? a : b;
    const JointBodyPose& g = s == 0 ? c : d;
    side.rx = x.q.apply(side.local_body - x.local_center);
    side.rg = g.q.apply(side.local_ground - g.local_center);
    side.u = g.q.apply(side.local_axis);
  }
}

void warmStartGear(Joint& j, const JointBodies& bodies) { warmStartRows(j, bodies); }

void solveGear(Joint& j, const JointBodies& bodies, const JointStep& step, bool use_bias) {
  solveEqualityRows(j, bodies, step, use_bias);  // the row: joint_rows.cpp
}

void gearRow(const Joint& j, const JointBodies& bodies, double jacobian[4][3], double& error) {
  const GearRow r = row(j, bodies);
  // Bodies a, b, c, d: A and B the geared ones, C and D their grounds (minus signs).
  jacobian[0][0] = r.jv[0].x(); jacobian[0][1] = r.jv[0].y(); jacobian[0][2] = r.jw_x[0];
  jacobian[1][0] = r.jv[1].x(); jacobian[1][1] = r.jv[1].y(); jacobian[1][2] = r.jw_x[1];
  jacobian[2][0] = -r.jv[0].x(); jacobian[2][1] = -r.jv[0].y(); jacobian[2][2] = -r.jw_g[0];
  jacobian[3][0] = -r.jv[1].x(); jacobian[3][1] = -r.jv[1].y(); jacobian[3][2] = -r.jw_g[1];
  error = r.coordinate - j.gear_constant;
}

// The coordinate sum now, for the constant at creation (world_joint.cpp).
double gearCoordinate(const Joint& j, const JointBodies& bodies) { return row(j, bodies).coordinate; }

}  // namespace rigidlab
