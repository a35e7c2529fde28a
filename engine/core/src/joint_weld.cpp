// Weld joint: b is glued to a. The relative angle (1 row) then the anchors' separation (2 rows),
// each rigid (the joints' stiffness) or soft with its own hertz and damping ratio (Box2D v3
// weld_joint.c). A soft weld is a spring: it acts in the relax pass too, and the position pass of
// sequential impulses leaves it alone.
#include "joint.h"
#include "joint_rows.h"

namespace rigidlab {

void prepareWeld(Joint& j, const JointStep& step) {
  const double k = j.ia + j.ib;
  j.axial_mass = k > 0.0 ? 1.0 / k : 0.0;
  j.linear_soft = j.def.linear_hertz > 0.0 ? makeSoft(j.def.linear_hertz, j.def.linear_damping, step.h) : step.soft;
  j.angular_soft = j.def.angular_hertz > 0.0 ? makeSoft(j.def.angular_hertz, j.def.angular_damping, step.h) : step.soft;
}

void solveWeld(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias) {
  solveEqualityRows(j, {&a, &b, &a, &b}, step, use_bias);  // the angle, then the point (joint_rows.cpp)
}

}  // namespace rigidlab
