// The equality part of a joint as explicit rows (joint_rows.cpp): each row is one scalar constraint
// C(x) = 0 with its Jacobian over the joint's bodies, J = ∂Ċ/∂(v, ω), so that
//   Ċ = Σ_k J_k · (v_k, ω_k),   an impulse λ on the row changes v_k by m_k λ J_k (and ω_k by i_k λ J_kω).
// Rows are grouped as they are solved together (a revolute pin's two rows; a weld's angle, then its
// two point rows). The same rows serve the block Gauss–Seidel step of both solvers (solveRowGroup)
// and the direct solve of small islands (joint_direct.cpp), which removes the iterative solvers'
// weakness on chains and large mass ratios.
#pragma once

#include "joint.h"

namespace rigidlab {

struct JointRow {
  double j[4][3];   // Jacobian on bodies a, b, c, d: (v_x, v_y, ω)
  double error;     // C now [m or rad]
  double* impulse;  // the joint's accumulated impulse this row applies (JointImpulses field)
  double max_error; // the largest correction of C per position pass (kMaxLinearCorrection, ...)
};

struct RowGroup {
  int count = 0;
  JointRow rows[3];
  // The group's own spring, or nullptr for the joints' rigid constraint (the step's position bias).
  const Softness* spring = nullptr;
};

// The joint's equality rows at the bodies' current state (joint.h views), at most two groups.
int equalityGroups(Joint& j, const JointBodies& bodies, RowGroup groups[2]);

// One block Gauss–Seidel step on a group: with K = J M⁻¹ Jᵀ,
//   λ = −s K⁻¹ (Ċ + β C) − a P   (s, β, a the softness; rigid without bias: s = 1, β = a = 0)
// accumulated into P and applied to the bodies.
void solveRowGroup(const RowGroup& g, const JointBodies& bodies, const JointStep& step, bool use_bias);

// Applies the impulses the joint's rows have accumulated (the warm start of row-only joints).
void warmStartRows(Joint& j, const JointBodies& bodies);
// The gear's one row (joint_gear.cpp).
void gearRow(const Joint& j, const JointBodies& bodies, double jacobian[4][3], double& error);

// The joint's rows solved by Gauss–Seidel: every group of the joint in turn.
void solveEqualityRows(Joint& j, const JointBodies& bodies, const JointStep& step, bool use_bias);

}  // namespace rigidlab
