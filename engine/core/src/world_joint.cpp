// Joints in the world: creation (validation, frames in body coordinates), removal, readings.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "rigidlab/error.h"
#include "rigidlab/world.h"
#include "world_impl.h"

namespace rigidlab {
namespace {

Transform transformOf(const WorldImpl& w, uint32_t slot) {
  return slot == kWorldSlot ? Transform{} : w.bodies[slot].xf;
}
double angleOf(const WorldImpl& w, uint32_t slot) { return slot == kWorldSlot ? 0.0 : w.bodies[slot].angle; }

// A force or torque bound: ≥ 0, and infinity means unlimited (a motor that always reaches its speed).
void requireBound(const char* field, double x) {
  if (!(x >= 0.0)) throw InputError(field, std::string(field) + " must be >= 0 (or inf: unlimited), got " + formatNumber(x));
}

// The tunables every type shares, and each type's own: refused with the field's name and value.
void validateTunables(const JointDef& d) {
  if (!(d.break_force > 0.0) || std::isnan(d.break_force))
    throw InputError("break_force", "break_force must be > 0, got " + formatNumber(d.break_force));
  if (!(d.break_torque > 0.0) || std::isnan(d.break_torque))
    throw InputError("break_torque", "break_torque must be > 0, got " + formatNumber(d.break_torque));
  requireFinite("lower", d.lower);
  requireFinite("upper", d.upper);
  if (d.enable_limit && d.lower > d.upper && d.type != JointType::Distance)
    throw InputError("lower", "lower (" + formatNumber(d.lower) + ") must not exceed upper (" + formatNumber(d.upper) + ")");
  requireFinite("motor_speed", d.motor_speed);
  requireBound("max_motor_torque", d.max_motor_torque);
  requireBound("max_motor_force", d.max_motor_force);
  requireNonNegative("spring_hertz", d.spring_hertz);
  requireNonNegative("spring_damping", d.spring_damping);
  requireNonNegative("linear_hertz", d.linear_hertz);
  requireNonNegative("linear_damping", d.linear_damping);
  requireNonNegative("angular_hertz", d.angular_hertz);
  requireNonNegative("angular_damping", d.angular_damping);
  requireNonNegative("motor_hertz", d.motor_hertz);
  requireNonNegative("motor_damping", d.motor_damping);
  requireFinite("linear_offset", d.linear_offset);
  requireFinite("angular_offset", d.angular_offset);
  requireFinite("linear_velocity", d.linear_velocity);
  requireFinite("angular_velocity", d.angular_velocity);
  requireBound("max_force", d.max_force);
  requireBound("max_torque", d.max_torque);
  if (d.type == JointType::Distance) {
    requireNonNegative("min_length", d.min_length);
    if (!(d.max_length >= 0.0)) throw InputError("max_length", "max_length must be >= 0, got " + formatNumber(d.max_length));
    if (d.min_length > d.max_length)
      throw InputError("min_length", "min_length (" + formatNumber(d.min_length) + ") must not exceed max_length (" +
                                         formatNumber(d.max_length) + ")");
    if (!(d.max_spring_force >= 0.0))
      throw InputError("max_spring_force", "max_spring_force must be >= 0, got " + formatNumber(d.max_spring_force));
  }
}

void copyTunables(JointDef& to, const JointDef& from) {
  to.length = from.length;  // distance: the rest length; pulley: the rope's constant (updateJoint)
  to.ratio = from.ratio;    // gear and pulley (updateJoint)
  to.collide_connected = from.collide_connected;
  to.break_force = from.break_force;
  to.break_torque = from.break_torque;
  to.name = from.name;
  to.enable_limit = from.enable_limit;
  to.lower = from.lower;
  to.upper = from.upper;
  to.enable_motor = from.enable_motor;
  to.motor_speed = from.motor_speed;
  to.max_motor_torque = from.max_motor_torque;
  to.max_motor_force = from.max_motor_force;
  to.enable_spring = from.enable_spring;
  to.spring_hertz = from.spring_hertz;
  to.spring_damping = from.spring_damping;
  to.min_length = from.min_length;
  to.max_length = from.max_length;
  to.max_spring_force = from.max_spring_force;
  to.linear_hertz = from.linear_hertz;
  to.linear_damping = from.linear_damping;
  to.angular_hertz = from.angular_hertz;
  to.angular_damping = from.angular_damping;
  to.motor_hertz = from.motor_hertz;
  to.motor_damping = from.motor_damping;
  to.linear_velocity = from.linear_velocity;
  to.angular_velocity = from.angular_velocity;
  to.max_force = from.max_force;
  to.max_torque = from.max_torque;
}

// One geared joint's coordinate now: its angle, or its translation along its axis.
double gearedCoordinate(const WorldImpl& w, const Joint& j) {
  if (j.def.type == JointType::Revolute) return angleOf(w, j.b) - angleOf(w, j.a) - j.reference_angle;
  const Transform xa = transformOf(w, j.a), xb = transformOf(w, j.b);
  return xa.q.apply(j.local_axis).dot(xb.apply(j.local_b) - xa.apply(j.local_a));
}

}  // namespace

bool WorldImpl::jointBlocksCollision(uint32_t a, uint32_t b) const {
  const auto& list = body_joints[a].size() <= body_joints[b].size() ? body_joints[a] : body_joints[b];
  for (uint32_t k : list) {
    const Joint& j = joints[k];
    if (!j.def.collide_connected && ((j.a == a && j.b == b) || (j.a == b && j.b == a))) return true;
  }
  return false;
}

JointId World::createJoint(const JointDef& in) {
  ++impl_->joint_edits;  // the energy watch lists the joints that put energy in anew
  WorldImpl& w = *impl_;
  w.requireUnlocked("createJoint");
  JointDef d = in;
  validateTunables(d);
  Joint j;
  if (d.type == JointType::Gear && d.joint_a.isNull() && d.joint_b.isNull()) {
    // Two bodies' angles geared: each side a revolute coordinate against the world,
    // θ_a + ratio · θ_b constant (Chipmunk's cpGearJoint; the ratio as the joint form's).
    if (d.a.isNull() || d.b.isNull()) throw InputError(d.a.isNull() ? "a" : "b", "a gear of bodies needs two bodies, a and b");
    w.get(d.a);
    w.get(d.b);
    if (d.a == d.b) throw InputError("b", "b must be another body than a");
    if (!std::isfinite(d.ratio) || d.ratio == 0.0) throw InputError("ratio", "ratio must be finite and not 0, got " + formatNumber(d.ratio));
    j.a = d.a.index;
    j.b = d.b.index;
    j.c = j.d = kWorldSlot;
    j.joint_a = j.joint_b = kNoJoint;
    for (Joint::GearSide& side : j.gear) side.revolute = true;
    j.gear_constant = w.bodies[j.a].angle + d.ratio * w.bodies[j.b].angle;
  } else if (d.type == JointType::Gear) {
    if (!d.a.isNull() || !d.b.isNull())
      throw InputError(d.a.isNull() ? "b" : "a", "a gear joins two joints (joint_a, joint_b) or two bodies (a, b), not both");
    const auto geared = [&](JointId id, const char* field) -> const Joint& {
      if (id.index >= w.joints.size() || !w.joints[id.index].alive || w.joints[id.index].generation != id.generation)
        throw InputError(field, std::string(field) + " is not a valid joint (it was removed or never existed)");
      const Joint& g = w.joints[id.index];
      if (g.def.type != JointType::Revolute && g.def.type != JointType::Prismatic)
        throw InputError(field, std::string(field) + " must be a revolute or prismatic joint, got a " + jointTypeName(g.def.type) + " joint");
      return g;
    };
    const Joint& ga = geared(d.joint_a, "joint_a");
    const Joint& gb = geared(d.joint_b, "joint_b");
    if (d.joint_a == d.joint_b) throw InputError("joint_b", "joint_b must be another joint than joint_a");
    if (!std::isfinite(d.ratio) || d.ratio == 0.0) throw InputError("ratio", "ratio must be finite and not 0, got " + formatNumber(d.ratio));
    // Side s: the geared body is the joint's b, turning against the joint's a.
    for (int s = 0; s < 2; ++s) {
      const Joint& g = s == 0 ? ga : gb;
      Joint::GearSide& side = j.gear[s];
      side.revolute = g.def.type == JointType::Revolute;
      side.local_ground = g.local_a;
      side.local_body = g.local_b;
      side.local_axis = g.local_axis;
      side.reference = g.reference_angle;
    }
    j.a = ga.b;
    j.c = ga.a;
    j.b = gb.b;
    j.d = gb.a;
    j.joint_a = d.joint_a.index;
    j.joint_b = d.joint_b.index;
    j.gear_constant = gearedCoordinate(w, ga) + d.ratio * gearedCoordinate(w, gb);
    // For reading back: each side's body that turns (the geared joint's b, or its a if b is the world).
    const uint32_t ta = j.a != kWorldSlot ? j.a : j.c, tb = j.b != kWorldSlot ? j.b : j.d;
    d.a = ta == kWorldSlot ? BodyId{} : w.bodies[ta].id;
    d.b = tb == kWorldSlot ? BodyId{} : w.bodies[tb].id;
  } else {
    if (d.a.isNull() && d.b.isNull()) throw InputError("a", "a joint needs a body (a), and b or the world");
    if (!d.a.isNull()) w.get(d.a);
    if (!d.b.isNull()) w.get(d.b);
    if (d.a == d.b) throw InputError("b", "b must be another body than a");
    j.a = d.a.isNull() ? kWorldSlot : d.a.index;
    j.b = d.b.isNull() ? kWorldSlot : d.b.index;
    requireFinite("anchor_a", d.anchor_a);
    requireFinite("anchor_b", d.anchor_b);
    const bool two_anchors = d.type == JointType::Distance || d.type == JointType::Pulley;
    if (!two_anchors) d.anchor_b = d.anchor_a;
    const Transform xa = transformOf(w, j.a), xb = transformOf(w, j.b);
    j.local_a = xa.applyInverse(d.anchor_a);
    j.local_b = xb.applyInverse(d.anchor_b);
    // Anchors in body coordinates: used as given; the world anchors follow (for reading back).
    if (d.local_anchor_a) j.local_a = requireFinite("local_anchor_a", *d.local_anchor_a);
    if (d.local_anchor_b) j.local_b = requireFinite("local_anchor_b", *d.local_anchor_b);
    if (d.local_anchor_a || d.local_anchor_b) {
      d.anchor_a = xa.apply(j.local_a);
      d.anchor_b = xb.apply(j.local_b);
    }
    // The solver squares lever arms and lengths: an anchor so far from its body that they overflow
    // is refused, naming it (not left to freeze both bodies in the first step).
    for (const auto& [field, local, anchor, side] : {std::tuple{"anchor_a", &j.local_a, &d.anchor_a, "a"},
                                                     std::tuple{"anchor_b", &j.local_b, &d.anchor_b, "b"}})
      if (!isFinite(*local) || !std::isfinite(local->squaredNorm()))
        throw InputError(field, std::string(field) + " " + formatVec(*anchor) + " is too far from body " + side +
                                    ": the lever arm overflows");
    j.reference_angle = angleOf(w, j.b) - angleOf(w, j.a);
    if (d.reference_angle && d.type != JointType::Motor) j.reference_angle = requireFinite("reference_angle", *d.reference_angle);
    if (d.type == JointType::Prismatic || d.type == JointType::Wheel) {
      requireFinite("axis", d.axis);
      if (!(d.axis.norm() > 0.0)) throw InputError("axis", "axis must not be zero, got " + formatVec(d.axis));
      // A direction whose length overflows is scaled first (its square would make it zero).
      const Vec2 axis = std::isfinite(d.axis.squaredNorm()) ? d.axis : Vec2(d.axis / d.axis.cwiseAbs().maxCoeff());
      j.local_axis = xa.q.applyInverse(axis.normalized());
    }
    if (d.type == JointType::Distance) {
      if (d.length < 0.0 && !std::isfinite((d.anchor_b - d.anchor_a).squaredNorm()))
        throw InputError("anchor_b", "anchor_b " + formatVec(d.anchor_b) + " is too far from anchor_a " +
                                         formatVec(d.anchor_a) + ": the length between them overflows");
      if (d.length < 0.0) d.length = (d.anchor_b - d.anchor_a).norm();
      requireFinite("length", d.length);
      j.length = d.length;
    }
    if (d.type == JointType::Motor) {
      if (d.use_offsets) {
        j.local_a = d.linear_offset;
        j.reference_angle = d.angular_offset;
      } else {
        d.linear_offset = j.local_a;
        d.angular_offset = j.reference_angle;
      }
    }
    if (d.type == JointType::Pulley) {
      requireFinite("ground_a", d.ground_a);
      requireFinite("ground_b", d.ground_b);
      if (!(std::isfinite(d.ratio) && d.ratio > 0.0)) throw InputError("ratio", "ratio must be > 0, got " + formatNumber(d.ratio));
      const double la = (d.anchor_a - d.ground_a).norm(), lb = (d.anchor_b - d.ground_b).norm();
      if (!(la > 1e-6)) throw InputError("anchor_a", "anchor_a must not be at ground_a (the rope needs a length)");
      if (!(lb > 1e-6)) throw InputError("anchor_b", "anchor_b must not be at ground_b (the rope needs a length)");
      j.length = la + d.ratio * lb;
      d.length = j.length;
    }
  }
  const auto dynamic = [&](uint32_t slot) { return slot != kWorldSlot && w.bodies[slot].isDynamic(); };
  if (!dynamic(j.a) && !dynamic(j.b) && !(d.type == JointType::Gear && (dynamic(j.c) || dynamic(j.d))))
    throw InputError("b", "at least one of the joint's bodies must be dynamic (a joint between static or kinematic bodies does nothing)");

  setJointDef(j, d);
  j.alive = true;
  uint32_t index;
  if (!w.free_joints.empty()) {
    index = w.free_joints.back();
    w.free_joints.pop_back();
    j.generation = w.joints[index].generation;
    w.joints[index] = std::move(j);
  } else {
    index = static_cast<uint32_t>(w.joints.size());
    w.joints.push_back(std::move(j));
  }
  Joint& made = w.joints[index];
  w.body_joints.resize(w.bodies.size());
  for (uint32_t slot : {made.a, made.b, made.c, made.d})
    if (slot != kWorldSlot && std::find(w.body_joints[slot].begin(), w.body_joints[slot].end(), index) == w.body_joints[slot].end())
      w.body_joints[slot].push_back(index);
  w.shapesEdited();  // a jointed body's shapes are looked at closer (collide_connected)
  // A joint between bodies all created asleep in this step, before it runs (a welded wall built at
  // rest), leaves them asleep, as a shape added to such a body does (createShape): the step's
  // islands join them, and they sleep and wake together. Static bodies keep nothing awake. Any
  // other joint wakes its bodies: what it holds may now move.
  bool all_created_asleep = true;
  for (uint32_t slot : {made.a, made.b, made.c, made.d})
    if (slot != kWorldSlot && !w.bodies[slot].isStatic())
      all_created_asleep = all_created_asleep && !w.bodies[slot].awake &&
                           w.created_asleep_before[slot] == w.step_count + 1;
  if (!all_created_asleep)
    for (uint32_t slot : {made.a, made.b, made.c, made.d})
      if (slot != kWorldSlot) w.wakeIsland(slot);
  return {index, made.generation};
}

void WorldImpl::releaseJoint(uint32_t index) {
  Joint& j = joints[index];
  for (uint32_t slot : {j.a, j.b, j.c, j.d}) {
    if (slot == kWorldSlot || slot >= body_joints.size()) continue;
    std::erase(body_joints[slot], index);
    wakeIsland(slot);  // what the joint held may now move
  }
  shapesEdited();
  const uint32_t generation = j.generation + 1;
  j = Joint{};
  j.generation = generation;
  free_joints.push_back(index);
  // A gear goes with either of its joints.
  for (uint32_t k = 0; k < joints.size(); ++k)
    if (joints[k].alive && joints[k].def.type == JointType::Gear && joints[k].joint_a != kNoJoint &&
        (joints[k].joint_a == index || joints[k].joint_b == index))
      releaseJoint(k);
}

void World::destroyJoint(JointId id) {
  ++impl_->joint_edits;  // the energy watch lists the joints that put energy in anew
  WorldImpl& w = *impl_;
  w.requireUnlocked("destroyJoint");
  w.get(id);
  w.releaseJoint(id.index);
}

Joint& WorldImpl::get(JointId id) {
  if (id.index >= joints.size() || !joints[id.index].alive || joints[id.index].generation != id.generation)
    throw InputError("joint", "joint handle is not valid (the joint was removed, broke, or never existed)");
  return joints[id.index];
}

bool World::isValid(JointId id) const {
  const WorldImpl& w = *impl_;
  return id.index < w.joints.size() && w.joints[id.index].alive && w.joints[id.index].generation == id.generation;
}

const JointDef& World::joint(JointId id) const { return impl_->get(id).def; }

void World::updateJoint(JointId id, const JointDef& def) {
  ++impl_->joint_edits;  // the energy watch lists the joints that put energy in anew
  WorldImpl& w = *impl_;
  w.requireUnlocked("updateJoint");
  Joint& j = w.get(id);
  JointDef checked = j.def;
  copyTunables(checked, def);
  if (j.def.type == JointType::Motor) {  // the target pose is the motor's to change
    checked.linear_offset = def.linear_offset;
    checked.angular_offset = def.angular_offset;
  }
  validateTunables(checked);
  // The length and ratio may change at run time (distance, gear, pulley); the other kinds keep theirs.
  const bool length_changed = checked.length != j.def.length, ratio_changed = checked.ratio != j.def.ratio;
  if (j.def.type == JointType::Distance) {
    if (!(std::isfinite(checked.length) && checked.length >= 0.0))
      throw InputError("length", "length must be >= 0, got " + formatNumber(checked.length));
  } else if (j.def.type == JointType::Pulley) {
    if (!(std::isfinite(checked.ratio) && checked.ratio > 0.0))
      throw InputError("ratio", "ratio must be > 0, got " + formatNumber(checked.ratio));
    if (!(std::isfinite(checked.length) && checked.length >= 0.0))
      throw InputError("length", "length must be >= 0, got " + formatNumber(checked.length));
  } else if (j.def.type == JointType::Gear) {
    checked.length = j.def.length;
    if (!std::isfinite(checked.ratio) || checked.ratio == 0.0)
      throw InputError("ratio", "ratio must be finite and not 0, got " + formatNumber(checked.ratio));
  } else {
    checked.length = j.def.length;
    checked.ratio = j.def.ratio;
  }
  if (j.def.type == JointType::Motor) {
    j.local_a = checked.linear_offset;
    j.reference_angle = checked.angular_offset;
  }
  if (j.def.type == JointType::Distance) j.length = checked.length;
  if (j.def.type == JointType::Pulley) {
    // A new ratio keeps the ropes as they are now (the constant follows); a new length is the constant.
    if (length_changed) {
      j.length = checked.length;
    } else if (ratio_changed) {
      const JointState now = jointState(id);
      j.length = (now.world_anchor_a - checked.ground_a).norm() + checked.ratio * (now.world_anchor_b - checked.ground_b).norm();
      checked.length = j.length;
    }
  }
  if (j.def.type == JointType::Gear && ratio_changed) {
    // The coupling holds from where the bodies are now: coordinate_1 + ratio · coordinate_2 at the new ratio.
    const double c1 = j.joint_a == kNoJoint ? angleOf(w, j.a) : gearedCoordinate(w, w.joints[j.joint_a]);
    const double c2 = j.joint_a == kNoJoint ? angleOf(w, j.b) : gearedCoordinate(w, w.joints[j.joint_b]);
    j.gear_constant = c1 + checked.ratio * c2;
  }
  setJointDef(j, checked);
  for (uint32_t slot : {j.a, j.b, j.c, j.d})
    if (slot != kWorldSlot) w.wakeIsland(slot);
}

JointState World::jointState(JointId id) const {
  const WorldImpl& w = *impl_;
  const Joint& j = const_cast<WorldImpl&>(w).get(id);
  JointState s;
  const Transform xa = transformOf(w, j.a), xb = transformOf(w, j.b);
  s.world_anchor_a = xa.apply(j.local_a);
  s.world_anchor_b = xb.apply(j.local_b);
  const auto velocityAt = [&](uint32_t slot, const Vec2& p) {
    return slot == kWorldSlot ? Vec2(Vec2::Zero()) : w.bodies[slot].pointVelocity(p);
  };
  const double wa = j.a == kWorldSlot ? 0.0 : w.bodies[j.a].angular_velocity;
  const double wb = j.b == kWorldSlot ? 0.0 : w.bodies[j.b].angular_velocity;
  s.angle = angleOf(w, j.b) - angleOf(w, j.a) - j.reference_angle;
  s.speed = wb - wa;
  const Vec2 d = s.world_anchor_b - s.world_anchor_a;
  if (j.def.type == JointType::Prismatic || j.def.type == JointType::Wheel) {
    const Vec2 axis = xa.q.apply(j.local_axis);
    s.axis = axis;
    s.translation = axis.dot(d);
    // d/dt (a · d) = a · (v_pB − v_pA) + (ω_A × a) · d
    const double along = axis.dot(velocityAt(j.b, s.world_anchor_b) - velocityAt(j.a, s.world_anchor_a)) + cross(wa, axis).dot(d);
    if (j.def.type == JointType::Prismatic) s.speed = along;
  } else if (j.def.type == JointType::Distance) {
    s.translation = d.norm();
  }
  jointReaction(j, s.reaction_force, s.reaction_torque);
  s.broken = j.broken;
  s.local_anchor_a = j.local_a;
  s.local_anchor_b = j.local_b;
  if (j.impulse_h > 0.0 && j.def.enable_motor &&
      (j.def.type == JointType::Revolute || j.def.type == JointType::Wheel || j.def.type == JointType::Prismatic))
    s.motor = j.impulses.motor / j.impulse_h;  // the motor's impulse over the last step
  return s;
}

std::vector<JointId> World::jointIds() const {
  std::vector<JointId> ids;
  for (uint32_t i = 0; i < impl_->joints.size(); ++i)
    if (impl_->joints[i].alive) ids.push_back({i, impl_->joints[i].generation});
  return ids;
}

std::optional<JointId> World::findJoint(std::string_view name) const {
  for (uint32_t i = 0; i < impl_->joints.size(); ++i)
    if (impl_->joints[i].alive && impl_->joints[i].def.name == name) return JointId{i, impl_->joints[i].generation};
  return std::nullopt;
}

std::vector<JointId> World::jointsOf(BodyId body) const {
  const WorldImpl& w = *impl_;
  const_cast<WorldImpl&>(w).get(body);
  std::vector<JointId> ids;
  if (body.index < w.body_joints.size())
    for (uint32_t k : w.body_joints[body.index]) ids.push_back({k, w.joints[k].generation});
  return ids;
}

std::vector<World::JointBreakInfo> World::jointBreaks() const {
  std::vector<JointBreakInfo> out;
  for (const WorldImpl::JointBreak& b : impl_->joint_breaks) out.push_back({b.id, b.def, b.force, b.torque});
  return out;
}

// After the solve: joints whose reaction exceeded a threshold break (they are removed now, with
// the reaction that broke them kept for the step's events).
void breakJoints(WorldImpl& w) {
  w.joint_breaks.clear();
  for (uint32_t k = 0; k < w.joints.size(); ++k) {
    Joint& j = w.joints[k];
    if (!j.alive || !j.breakable) continue;
    Vec2 force;
    double torque;
    jointReaction(j, force, torque);
    if (force.norm() <= j.def.break_force && std::abs(torque) <= j.def.break_torque) continue;
    j.broken = true;
    w.joint_breaks.push_back({{k, j.generation}, j.def, force, torque});
  }
  for (const WorldImpl::JointBreak& b : w.joint_breaks)
    if (w.joints[b.id.index].alive && w.joints[b.id.index].generation == b.id.generation) w.releaseJoint(b.id.index);
}

}  // namespace rigidlab
