// Joints inside the solvers (joint_solver.h).
#include "rigidlab/portable_math.h"
#include "joint_solver.h"

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

// A body of the position pass: no velocity, its displacement and rotation since the joint was
// prepared (joint.h), its inverse masses (0: immovable). The velocity the solve leaves is the
// correction.
SoftBody positionView(const Body& b, const Vec2& center0, double angle0, double im, double ii) {
  const Vec2 d = b.center - center0;
  double sin_q = 0.0, cos_q = 1.0;
  portableSinCos(b.angle - angle0, sin_q, cos_q);
  return {0.0, 0.0, 0.0, d.x(), d.y(), cos_q, sin_q, im, ii};
}

}  // namespace

void correctJointPositions(WorldImpl& w) {
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
      done[slot] = 1;
      if (!w.solved.empty() && slot < w.overlap_weight.size() && w.overlap_weight[slot] > 0.0) continue;
      Body& b = w.bodies[slot];
      b.center += kappa * w.dt * (b.velocity - w.solve_start_velocity[slot]);
      b.angle += kappa * w.dt * (b.angular_velocity - w.solve_start_angular_velocity[slot]);
      WorldImpl::syncTransform(b);
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
      const Vec2 centers[4] = {j.center_a0, j.center_b0, j.center_c0, j.center_d0};
      const double angles[4] = {j.angle_a0, j.angle_b0, j.angle_c0, j.angle_d0};
      SoftBody views[4];
      for (int i = 0; i < 4; ++i) {
        if (slots[i] == kWorldSlot) {
          views[i] = {0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
        } else {
          const Body& b = w.bodies[slots[i]];  // a still body (static, asleep): where it is, immovable
          const bool moves = w.isActive(slots[i]);
          views[i] = positionView(b, centers[i], angles[i], moves ? b.inv_mass : 0.0, moves ? b.inv_inertia : 0.0);
        }
      }
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
        Body& b = w.bodies[slots[i]];
        const SoftBody& v = views[i];
        if (v.vx == 0.0 && v.vy == 0.0 && v.w == 0.0) continue;
        b.center += Vec2(v.vx, v.vy);
        b.angle += v.w;
        WorldImpl::syncTransform(b);
        largest = std::max({largest, std::abs(v.vx), std::abs(v.vy), std::abs(v.w)});
      }
    }
    if (largest < kTolerance) break;
  }
  newton += directJointPositions(w);  // the passes' limits may have opened the equalities a little
  directJointVelocitiesAtPositions(w);
  w.stats.joint_position_passes = passes + 1;
  w.stats.joint_newton_steps = newton;
}

}  // namespace rigidlab
