// Joints inside the world: one implementation per type (joint_<type>.cpp), which both contact
// solvers call, in the way Box2D v3 solves joints (prepare, warm start, solve with or without the
// position bias, relax).
//
// A joint's bodies, as the solvers hand them over, are SoftBody records (contact.h): velocity,
// displacement and rotation since the joint was prepared, inverse mass and inertia. The joint finds
// its current anchors and errors from those, without collision detection:
//   r_A = q_A r_A0,   d = Δc_B − Δc_A + (c_B0 − c_A0) + r_B − r_A   (the anchors' separation)
//   θ = θ_B − θ_A − θ_ref = (θ_B0 − θ_A0 − θ_ref) + angle(q_A⁻¹ q_B)
// - the soft step (soft_step.cpp) prepares joints at the step's detection state and, in each
//   sub-step, warm starts them, solves them with the soft position bias, moves the bodies, and
//   relaxes them (the solve without bias);
// - sequential impulses (contact_solver.cpp) solve them on velocities only (no bias: the bodies do
//   not move during the solve), then position_correction.cpp removes their position error by
//   nonlinear Gauss–Seidel, calling the same solve in "position" mode: the bodies' velocities are
//   zero, the rigid bias is the whole error (C/h with h = 1), motors and springs are left out, the
//   impulses start from zero, and the velocity it finds is applied as a displacement.
#pragma once

#include "rigidlab/portable_math.h"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "contact.h"
#include "rigidlab/joint.h"
#include "softness.h"

namespace rigidlab {

constexpr uint32_t kWorldSlot = UINT32_MAX;  // a joint's "body" b when it is pinned to the world
constexpr uint32_t kNoJoint = UINT32_MAX;    // Joint::joint_a, joint_b of a gear of two bodies

// Accumulated impulses, carried between steps for warm starting (each type uses what it needs).
struct JointImpulses {
  double linear_x = 0.0, linear_y = 0.0;  // point constraint (revolute, weld, motor, friction)
  double angular = 0.0;                   // weld, motor, friction; prismatic's angle
  double perpendicular = 0.0;             // prismatic, wheel: across the axis
  double axial = 0.0;                     // distance (rigid and spring), pulley, gear
  double spring = 0.0, motor = 0.0, lower = 0.0, upper = 0.0;
  double spring_x = 0.0, spring_y = 0.0;  // motor joint's linear spring
};

struct Joint {
  // --- What the solvers read on every pass, first and together (a joint grid's 20 000 joints
  // are passed over 24 times a step: the fewer cache lines each pass touches the better).
  JointType type = JointType::Revolute;                            // def.type
  bool enable_limit = false, enable_motor = false;  // def's, copied at prepare
  bool enable_spring = false;  // def.enable_spring with spring_hertz > 0
  bool alive = false;          // in use (its slot is not free)
  bool breakable = false;      // def's break force or torque is finite (setJointDef): breakJoints reads no further
  uint32_t a = 0, b = kWorldSlot;  // body slots
  uint32_t c = kWorldSlot, d = kWorldSlot;  // gear: the bodies its joints turn against (below)
  // Solver data, from prepare (world rotation, relative to the centres at the prepare state).
  Vec2 ra = Vec2::Zero(), rb = Vec2::Zero();
  Vec2 delta_center = Vec2::Zero();  // c_B − c_A
  double delta_angle = 0.0;          // θ_B − θ_A − reference (revolute, prismatic, weld, motor)
  double ma = 0.0, mb = 0.0, ia = 0.0, ib = 0.0;
  double axial_mass = 0.0;
  Softness spring;
  JointImpulses impulses;
  double lower = 0.0, upper = 0.0, motor_speed = 0.0, max_motor_torque = 0.0;  // def's, copied at prepare
  // Where the bodies were at prepare (sequential impulses' position pass and direct solves measure
  // displacements from there, every pass).
  Vec2 center_a0 = Vec2::Zero(), center_b0 = Vec2::Zero(), center_c0 = Vec2::Zero(), center_d0 = Vec2::Zero();
  double angle_a0 = 0.0, angle_b0 = 0.0, angle_c0 = 0.0, angle_d0 = 0.0;

  JointDef def;  // as created (anchors and axis world at creation); tunables updated by World::updateJoint
  uint32_t generation = 0;
  bool broken = false;
  // Frames in body coordinates (b's in world coordinates when b is the world).
  Vec2 local_a = Vec2::Zero(), local_b = Vec2::Zero();
  Vec2 local_axis = Vec2(1.0, 0.0);  // unit, in a's frame
  double reference_angle = 0.0;      // θ_B − θ_A at creation (motor joint: the target)
  double length = 0.0;               // distance: rest length; pulley: the constant length_a + ratio · length_b
  // Gear: the geared joints, and the bodies c, d they turn against (side 0: a against c, side 1: b
  // against d). Each side's frame is copied from its joint when the gear is made. A gear of two
  // bodies (JointDef::joint_a null) has kNoJoint here and turns a and b against the world.
  uint32_t joint_a = 0, joint_b = 0;
  struct GearSide {
    bool revolute = true;
    Vec2 local_ground = Vec2::Zero();  // the joint's anchor on its ground (c or d), in that body's frame
    Vec2 local_body = Vec2::Zero();    // its anchor on the geared body (a or b)
    Vec2 local_axis = Vec2(1.0, 0.0);  // prismatic: in the ground's frame
    double reference = 0.0;            // revolute: the joint's reference angle
    Vec2 rg = Vec2::Zero(), rx = Vec2::Zero(), u = Vec2::Zero();  // prepared: world rotation
  } gear[2];
  double gear_constant = 0.0;  // coordinate_1 + ratio · coordinate_2 at creation

  Vec2 axis = Vec2(1.0, 0.0);        // world axis (prismatic, wheel) at prepare
  double mc = 0.0, md = 0.0, ic = 0.0, id = 0.0;
  Softness linear_soft, angular_soft;
  double impulse_h = 0.0;  // the step (or sub-step) length the impulses were accumulated over [s]
};

// Whether a definition lets its joint break (a finite break force or torque).
inline bool breakableDef(const JointDef& d) { return !std::isinf(d.break_force) || !std::isinf(d.break_torque); }
// Sets a joint's definition and what the head of Joint keeps of it.
inline void setJointDef(Joint& j, const JointDef& d) {
  j.def = d;
  j.breakable = breakableDef(d);
}

// What a joint's prepare reads of one body.
struct JointBodyPose {
  Vec2 center = Vec2::Zero();
  double angle = 0.0;
  Rot q;
  Vec2 local_center = Vec2::Zero();
  double inv_mass = 0.0, inv_inertia = 0.0;
};

struct JointStep {
  double h = 0.0, inv_h = 0.0;  // the step or sub-step
  Softness soft;                // the position bias of the joints' rigid constraints
  bool warm_starting = true;
  bool position = false;        // the position pass of sequential impulses (see the file comment)
};

struct JointBodies {
  SoftBody* a;
  SoftBody* b;
  SoftBody* c;  // gear only
  SoftBody* d;
};

void prepareJoint(Joint& j, const JointBodyPose& a, const JointBodyPose& b, const JointBodyPose* c,
                  const JointBodyPose* d, const JointStep& step);
void warmStartJoint(Joint& j, const JointBodies& bodies);
void solveJoint(Joint& j, const JointBodies& bodies, const JointStep& step, bool use_bias);
// The reaction on b of the impulses accumulated over `impulse_h`: force [N] and torque [N·m].
void jointReaction(const Joint& j, Vec2& force, double& torque);

// Per type (joint_<type>.cpp).
void prepareRevolute(Joint& j, const JointStep& step);
void solveRevolute(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias);
void prepareDistance(Joint& j, const JointStep& step);
void solveDistance(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias);
// Prismatic and wheel joints: the frame of their axis at the current state (joint_prismatic.cpp).
struct AxialFrame {
  Vec2 ra, rb, d, axis;
  double translation;  // a · d
  double a1, a2;       // (d + r_A) × a, r_B × a: the torques of an axial force
  double mass;         // 1/(m_A + m_B + i_A a₁² + i_B a₂²)
  double cdot(const SoftBody& a, const SoftBody& b) const {
    return axis.dot(Vec2(b.vx - a.vx, b.vy - a.vy)) + a2 * b.w - a1 * a.w;
  }
  void apply(SoftBody& a, SoftBody& b, double impulse) const {
    a.vx -= a.im * impulse * axis.x();
    a.vy -= a.im * impulse * axis.y();
    a.w -= a.ii * impulse * a1;
    b.vx += b.im * impulse * axis.x();
    b.vy += b.im * impulse * axis.y();
    b.w += b.ii * impulse * a2;
  }
};
AxialFrame axialFrame(const Joint& j, const SoftBody& a, const SoftBody& b);
// A one-sided row along the axis: C ≥ 0 with Ċ = sign · (axial velocity), impulse ≥ 0.
void solveAxialLimit(SoftBody& a, SoftBody& b, const AxialFrame& f, const JointStep& step, bool use_bias, double c,
                     double sign, double& accumulated);
void preparePrismatic(Joint& j, const JointStep& step);
void solvePrismatic(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias);
void prepareWheel(Joint& j, const JointStep& step);
void solveWheel(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias);
void prepareWeld(Joint& j, const JointStep& step);
void solveWeld(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias);
void prepareMotor(Joint& j, const JointStep& step);
void solveMotor(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias);
void preparePulley(Joint& j, const JointStep& step);
void warmStartPulley(Joint& j, SoftBody& a, SoftBody& b);
void solvePulley(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias);
void prepareGear(Joint& j, const JointBodyPose& a, const JointBodyPose& b, const JointBodyPose& c, const JointBodyPose& d);
void warmStartGear(Joint& j, const JointBodies& bodies);
double gearCoordinate(const Joint& j, const JointBodies& bodies);  // coordinate_1 + ratio · coordinate_2
void solveGear(Joint& j, const JointBodies& bodies, const JointStep& step, bool use_bias);

// --- Shared pieces of the joints' maths.

// The body's anchor r_0 turned by its rotation since prepare.
inline Vec2 turned(const SoftBody& s, const Vec2& r) { return Vec2(s.qc * r.x() - s.qs * r.y(), s.qs * r.x() + s.qc * r.y()); }
// d = Δc_B − Δc_A + (c_B0 − c_A0) + r_B − r_A: the separation of the anchors now.
inline Vec2 anchorSeparation(const Joint& j, const SoftBody& a, const SoftBody& b, const Vec2& ra, const Vec2& rb) {
  return Vec2(b.dx - a.dx, b.dy - a.dy) + j.delta_center + rb - ra;
}
// θ_B − θ_A − θ_ref now: the angle at prepare plus the relative rotation since.
inline double relativeAngle(const Joint& j, const SoftBody& a, const SoftBody& b) {
  return j.delta_angle + portableAtan2(a.qc * b.qs - a.qs * b.qc, a.qc * b.qc + a.qs * b.qs);
}
// In the position pass an error is removed at most this much per iteration, so that a badly broken
// joint comes back over several steps instead of throwing its bodies (Box2D 2.4's limits).
constexpr double kMaxLinearCorrection = 0.2;   // [m]
constexpr double kMaxAngularCorrection = 0.14;  // [rad], 8°
inline double clampedError(const JointStep& step, double c, double max) {
  return step.position ? std::clamp(c, -max, max) : c;
}
inline Vec2 clampedError(const JointStep& step, const Vec2& c) {
  if (!step.position) return c;
  const double n = c.norm();
  return n > kMaxLinearCorrection ? Vec2(c * (kMaxLinearCorrection / n)) : c;
}
// Velocity of the anchor point r on the body: v + ω × r.
inline Vec2 pointVelocity(const SoftBody& s, const Vec2& r) { return Vec2(s.vx - s.w * r.y(), s.vy + s.w * r.x()); }
// The impulse P at anchors r_A, r_B: −P on A, +P on B, with the angular parts r × P (and an extra
// torque impulse L on both, −L on A).
inline void applyLinear(SoftBody& a, SoftBody& b, const Vec2& ra, const Vec2& rb, const Vec2& p) {
  a.vx -= a.im * p.x();
  a.vy -= a.im * p.y();
  a.w -= a.ii * cross(ra, p);
  b.vx += b.im * p.x();
  b.vy += b.im * p.y();
  b.w += b.ii * cross(rb, p);
}
inline void applyAngular(SoftBody& a, SoftBody& b, double l) {
  a.w -= a.ii * l;
  b.w += b.ii * l;
}
// K = [[m_A + m_B + i_A r_Ay² + i_B r_By², −i_A r_Ax r_Ay − i_B r_Bx r_By], [·, m_A + m_B + i_A r_Ax² + i_B r_Bx²]]:
// the point constraint's effective mass matrix; solves K x = rhs (x = 0 when K is singular). Inline:
// every pass of every revolute joint calls it, and a call returns x through memory.
inline Vec2 solvePointMatrix(const SoftBody& a, const SoftBody& b, const Vec2& ra, const Vec2& rb, const Vec2& rhs) {
  const double k11 = a.im + b.im + a.ii * ra.y() * ra.y() + b.ii * rb.y() * rb.y();
  const double k12 = -a.ii * ra.x() * ra.y() - b.ii * rb.x() * rb.y();
  const double k22 = a.im + b.im + a.ii * ra.x() * ra.x() + b.ii * rb.x() * rb.x();
  double det = k11 * k22 - k12 * k12;
  if (det == 0.0) return Vec2::Zero();
  det = 1.0 / det;
  return Vec2(det * (k22 * rhs.x() - k12 * rhs.y()), det * (k11 * rhs.y() - k12 * rhs.x()));
}
// The rigid point constraint d = 0 (revolute) as one 2×2 block: λ = −s K⁻¹ (Ċ + β d) − a P with the
// step's softness (s, β, a) when biased, λ = −K⁻¹ Ċ without; the same rows joint_rows.cpp writes
// for the direct solve.
void solvePointConstraint(Joint& j, SoftBody& a, SoftBody& b, const JointStep& step, bool use_bias);

}  // namespace rigidlab
