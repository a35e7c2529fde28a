// Joints inside the solvers (joint_solver.h).
#include "rigidlab/portable_math.h"
#include "joint_solver.h"

#include <bit>
#include <cmath>

#include "stages.h"
#include "world_impl.h"

namespace rigidlab {

JointBodyPose jointPose(const WorldImpl& w, uint32_t slot) {
  JointBodyPose p;
  if (slot == kWorldSlot) return p;
  const Body& b = w.bodies[slot];
  p.center = b.center;
  p.angle = b.angle;
  p.q = b.xf.q;
  p.local_center = b.local_center;
  if (w.isActive(slot)) {
    p.inv_mass = b.inv_mass;
    p.inv_inertia = b.inv_inertia;
  }
  return p;
}

void prepareJointAt(WorldImpl& w, Joint& j, const JointStep& step) {
  const JointBodyPose a = jointPose(w, j.a), b = jointPose(w, j.b);
  if (j.def.type == JointType::Gear) {
    const JointBodyPose c = jointPose(w, j.c), d = jointPose(w, j.d);
    prepareJoint(j, a, b, &c, &d, step);
  } else {
    prepareJoint(j, a, b, nullptr, nullptr, step);
  }
}

namespace {

// The sine and cosine of a body's rotation since its joints were prepared. They were all prepared
// at the same state, so until the body moves every view of it asks for the same angle: the last
// one is kept per body slot and reused when the angle has the same bits (the same input, the same
// result).
void rotationSinCos(WorldImpl& w, uint32_t slot, double angle, double& s, double& c) {
  auto& memo = w.joint_rotation;
  if (slot >= memo.size()) {
    WorldImpl::JointRotation none{0.0, 0.0, 1.0};
    portableSinCos(none.angle, none.s, none.c);
    memo.resize(w.bodies.size(), none);
  }
  WorldImpl::JointRotation& m = memo[slot];
  if (std::bit_cast<uint64_t>(m.angle) == std::bit_cast<uint64_t>(angle)) {
    s = m.s;
    c = m.c;
    return;
  }
  portableSinCos(angle, s, c);
  m = {angle, s, c};
}

// The marks of WorldImpl::joint_displaced.
constexpr char kDisplaced = 1;  // displaced by its joint impulses (or by its contacts), transform synced
constexpr char kMoved = 2;      // moved since its transform was synced

}  // namespace

SoftBody jointPositionView(WorldImpl& w, const Joint& j, int i) {
  const uint32_t slots[4] = {j.a, j.b, j.c, j.d};
  const uint32_t slot = slots[i];
  if (slot == kWorldSlot) return {0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
  const Vec2 centers[4] = {j.center_a0, j.center_b0, j.center_c0, j.center_d0};
  const double angles[4] = {j.angle_a0, j.angle_b0, j.angle_c0, j.angle_d0};
  const Body& b = w.bodies[slot];
  const Vec2 d = b.center - centers[i];
  double sin_q = 0.0, cos_q = 1.0;
  rotationSinCos(w, slot, b.angle - angles[i], sin_q, cos_q);
  const bool moves = w.isActive(slot);
  return {0.0, 0.0, 0.0, d.x(), d.y(), cos_q, sin_q, moves ? b.inv_mass : 0.0, moves ? b.inv_inertia : 0.0};
}

void moveJointBody(WorldImpl& w, uint32_t slot, const Vec2& dc, double d_angle) {
  Body& b = w.bodies[slot];
  b.center += dc;
  b.angle += d_angle;
  w.joint_displaced[slot] = kMoved;
}

void correctJointPositions(WorldImpl& w, double dt, const std::vector<double>& displaced) {
  if (w.si_joints.empty()) return;
  // The joints' bodies move by the displacement their joint impulses would have caused during the
  // step, as a persisting contact's do (position_correction.cpp): κ h Δv, κ the integrator's
  // weight of the velocity gained in a step. Bodies in contacts have had theirs.
  const double kappa = restingWeight(w.def.integrator);
  auto& done = w.joint_displaced;
  done.assign(w.bodies.size(), 0);
  for (uint32_t k : w.si_joints) {
    const Joint& j = w.joints[k];
    for (uint32_t slot : {j.a, j.b, j.c, j.d}) {
      if (slot == kWorldSlot || done[slot] || !w.isActive(slot)) continue;
      done[slot] = kDisplaced;
      if (slot < displaced.size() && displaced[slot] > 0.0) continue;
      const Body& b = w.bodies[slot];
      moveJointBody(w, slot, kappa * dt * (b.velocity - w.solve_start_velocity[slot]),
                    kappa * dt * (b.angular_velocity - w.solve_start_angular_velocity[slot]));
    }
  }
  int newton = directJointPositions(w);
  // A full correction per pass (C/h with h = 1), at most kMaxLinearCorrection; the impulses of the
  // velocity solve are kept aside (warm starting) and each pass starts from zero.
  JointStep step;
  step.h = step.inv_h = 1.0;
  step.soft = {1.0, 1.0, 0.0};
  step.position = true;
  constexpr int kPasses = 10;
  constexpr double kTolerance = 1e-5;  // [m] and [rad]: the correction of a pass that ends them
  int passes = 0;
  for (int pass = 0; pass < kPasses; ++pass, ++passes) {
    double largest = 0.0;
    const size_t count = w.si_joints.size();
    for (size_t q = 0; q < count; ++q) {
      Joint& j = w.joints[w.si_joints[q]];
      const uint32_t slots[4] = {j.a, j.b, j.c, j.d};
      // Made in place (a copy of a view just returned stalls on reading back its fields). A still
      // body: where it is, immovable.
      SoftBody views[4] = {jointPositionView(w, j, 0), jointPositionView(w, j, 1), jointPositionView(w, j, 2),
                           jointPositionView(w, j, 3)};
      // Aliased slots (a gear's grounds may be one body) share a view.
      SoftBody* ptr[4];
      for (int i = 0; i < 4; ++i) {
        ptr[i] = &views[i];
        for (int k2 = 0; k2 < i; ++k2)
          if (slots[k2] == slots[i] && slots[i] != kWorldSlot) ptr[i] = ptr[k2];
      }
      const JointImpulses kept = j.impulses;
      j.impulses = {};
      solveJoint(j, {ptr[0], ptr[1], ptr[2], ptr[3]}, step, true);
      j.impulses = kept;
      for (int i = 0; i < 4; ++i) {
        if (ptr[i] != &views[i] || slots[i] == kWorldSlot || !w.isActive(slots[i])) continue;
        const SoftBody& v = views[i];
        if (v.vx == 0.0 && v.vy == 0.0 && v.w == 0.0) continue;
        moveJointBody(w, slots[i], Vec2(v.vx, v.vy), v.w);
        largest = std::max({largest, std::abs(v.vx), std::abs(v.vy), std::abs(v.w)});
      }
    }
    if (largest < kTolerance) break;
  }
  newton += directJointPositions(w);  // the passes' limits may have opened the equalities a little
  directJointVelocitiesAtPositions(w);
  // The transforms of the bodies moved, at their final centres and angles.
  for (uint32_t k : w.si_joints) {
    const Joint& j = w.joints[k];
    for (uint32_t slot : {j.a, j.b, j.c, j.d})
      if (slot != kWorldSlot && done[slot] == kMoved) {
        WorldImpl::syncTransform(w.bodies[slot]);
        done[slot] = kDisplaced;
      }
  }
  w.stats.joint_position_passes = passes + 1;
  w.stats.joint_newton_steps = newton;
}

}  // namespace rigidlab
