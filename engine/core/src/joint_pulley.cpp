// Pulley joint: a rope from a's anchor over the fixed point ground_a, and from b's anchor over
// ground_b, keeps length_a + ratio · length_b constant (Box2D 2.4 b2PulleyJoint). With u_A, u_B
// the unit directions from the grounds to the anchors:
//   C = L_A + r L_B − L₀,  Ċ = u_A · v_pA + r u_B · v_pB
//   K = m_A + i_A (r_A × u_A)² + r² (m_B + i_B (r_B × u_B)²),  Δv_A = m_A λ u_A, Δv_B = m_B λ r u_B
#include "joint.h"
#include "joint_rows.h"

namespace rigidlab {

void preparePulley(Joint& j, const JointStep&) {
  const Vec2 pa = j.center_a0 + j.ra, pb = j.center_b0 + j.rb;
  const Vec2 db = pb - j.def.ground_b;
  j.axis = db.norm() > 1e-9 ? Vec2(db.normalized()) : Vec2::Zero();  // b's rope, for the reaction on b
  (void)pa;
}

void warmStartPulley(Joint& j, SoftBody& a, SoftBody& b) { warmStartRows(j, {&a, &b, &a, &b}); }

void solvePulley(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias) {
  solveEqualityRows(j, {&a, &b, &a, &b}, step, use_bias);  // the row: joint_rows.cpp
}

}  // namespace rigidlab
