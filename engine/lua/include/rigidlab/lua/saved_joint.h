// A joint as data that makes it again: what saving a world (scene_writer.cpp) and the sandbox's
// undo of a deleted body need.
//
// World::createJoint takes anchors and axes in world coordinates and stores them in its bodies'
// frames, and takes the joint's zero angle (its reference angle θ_B − θ_A) from the poses of the
// moment it is made. A joint that has worked for a while has its bodies turned (a hinge at 40°,
// a wheel's chassis tilted) and its anchors a little apart, so making it again from the current
// anchors would move its zero angle, limits and spring rest to where the bodies happen to be.
// Instead, one body is put for the moment of creation where it would be if the joint held
// exactly at its zero angle (`JointBuild::move`), the joint is made there, and the body is put
// back: the new joint reads the same angle, translation and anchors as the old one.
//
// When nothing has moved since the joint was made (a world saved before it ran), the creation
// anchors and axis of World::joint reproduce the joint's frames bit for bit and are used as they
// are, so the rebuilt world steps exactly like the original.
#pragma once

#include <cmath>
#include <optional>

#include "rigidlab/world.h"

namespace rigidlab::lua {

// Where a joint holds its bodies, in their own frames (World::jointState read back): anchors in
// a's and b's coordinates (world coordinates for the world), the prismatic and wheel axis in a's,
// and the reference angle. True wherever the bodies move.
struct JointFrames {
  Vec2 local_a = Vec2::Zero(), local_b = Vec2::Zero();
  Vec2 local_axis = Vec2(1.0, 0.0);
  double reference_angle = 0.0;
};

// The definition that makes the joint again between def.a and def.b where they are now, and the
// pose at which `moved` (one of them) must be while it is made (see the file comment).
struct JointBuild {
  JointDef def;
  bool move = false;
  BodyId moved;
  Vec2 position = Vec2::Zero();  // moved body's origin while the joint is made
  double angle = 0.0;
};

namespace saved_joint_detail {

inline Transform poseOf(const World& w, BodyId id) { return id.isNull() ? Transform{} : w.body(id).xf; }
inline double angleOf(const World& w, BodyId id) { return id.isNull() ? 0.0 : w.body(id).angle; }
// The world point p, stored in the frame xf as createJoint stores it, reads back as `reading`.
inline bool reproduces(const Transform& xf, const Vec2& p, const Vec2& reading) {
  return xf.apply(xf.applyInverse(p)) == reading;
}
inline bool singleAnchor(JointType t) {
  return t == JointType::Revolute || t == JointType::Prismatic || t == JointType::Weld || t == JointType::Wheel ||
         t == JointType::Friction;
}

// The joint's readings now: anchors (world), angle, axis (world).
struct Readings {
  Vec2 anchor_a, anchor_b, axis;
  double angle;
};

inline JointBuild fromReadings(const World& w, const JointDef& def, const Readings& r, BodyId prefer_moved) {
  JointBuild out;
  out.def = def;
  JointDef& d = out.def;
  const Transform xa = poseOf(w, def.a), xb = poseOf(w, def.b);
  const double angle_a = angleOf(w, def.a), angle_b = angleOf(w, def.b);
  const auto pick = [](const Transform& xf, const Vec2& creation, const Vec2& reading) {
    return reproduces(xf, creation, reading) ? creation : reading;
  };
  switch (def.type) {
    case JointType::Distance:
    case JointType::Pulley:
      d.anchor_a = pick(xa, def.anchor_a, r.anchor_a);
      d.anchor_b = pick(xb, def.anchor_b, r.anchor_b);
      return out;
    case JointType::Motor:  // b's anchor; the target (offsets) is kept in the definition
      d.use_offsets = true;
      d.anchor_a = d.anchor_b = pick(xb, def.anchor_a, r.anchor_b);
      return out;
    case JointType::Gear:
      return out;
    default:
      break;
  }
  if (def.type == JointType::Prismatic || def.type == JointType::Wheel) {
    const Vec2 creation = def.axis.normalized();
    d.axis = xa.q.apply(xa.q.applyInverse(creation)) == r.axis ? def.axis : r.axis;
  }
  // Made where the bodies are, the joint's zero angle would be θ_B − θ_A now.
  const bool at_zero = r.angle == 0.0;
  for (const Vec2& p : {def.anchor_a, r.anchor_a}) {
    if (at_zero && reproduces(xa, p, r.anchor_a) && reproduces(xb, p, r.anchor_b)) {
      d.anchor_a = d.anchor_b = p;
      return out;
    }
  }
  // Otherwise one body is put where it would be at the zero angle with the anchors together.
  const double reference = (angle_b - angle_a) - r.angle;
  const bool move_a = def.b.isNull() || (prefer_moved == def.a && !def.a.isNull());
  out.move = true;
  if (move_a) {
    out.moved = def.a;
    out.angle = angle_b - reference;
    const Vec2 local = xa.applyInverse(r.anchor_a);
    out.position = r.anchor_b - Rot::fromAngle(out.angle).apply(local);
    d.anchor_a = d.anchor_b = r.anchor_b;
  } else {
    out.moved = def.b;
    out.angle = angle_a + reference;
    const Vec2 local = xb.applyInverse(r.anchor_b);
    out.position = r.anchor_a - Rot::fromAngle(out.angle).apply(local);
    d.anchor_a = d.anchor_b = r.anchor_a;
  }
  return out;
}

}  // namespace saved_joint_detail

inline JointFrames jointFrames(const World& w, JointId id) {
  using namespace saved_joint_detail;
  const JointDef& def = w.joint(id);
  const JointState s = w.jointState(id);
  const Transform xa = poseOf(w, def.a), xb = poseOf(w, def.b);
  JointFrames f;
  f.local_a = xa.applyInverse(s.world_anchor_a);
  f.local_b = xb.applyInverse(s.world_anchor_b);
  f.local_axis = xa.q.applyInverse(s.axis);
  f.reference_angle = (angleOf(w, def.b) - angleOf(w, def.a)) - s.angle;
  return f;
}

// The joint `id` as a build: its definition with what saving needs (see the file comment).
inline JointBuild jointBuild(const World& w, JointId id) {
  using namespace saved_joint_detail;
  const JointState s = w.jointState(id);
  return fromReadings(w, w.joint(id), {s.world_anchor_a, s.world_anchor_b, s.axis, s.angle}, BodyId{});
}

// A joint of definition `def` (bodies def.a and def.b, live; its tunables) and frames `f`, made
// between those bodies where they are now. `prefer_moved`: the body to move if one must be (the
// one just created, so that a body in use is not moved and put back).
inline JointBuild jointBuild(const World& w, const JointDef& def, const JointFrames& f, BodyId prefer_moved = {}) {
  using namespace saved_joint_detail;
  const Transform xa = poseOf(w, def.a), xb = poseOf(w, def.b);
  const Readings r{xa.apply(f.local_a), xb.apply(f.local_b), xa.q.apply(f.local_axis),
                   (angleOf(w, def.b) - angleOf(w, def.a)) - f.reference_angle};
  return fromReadings(w, def, r, prefer_moved);
}

// Makes the joint (createJoint), moving `moved` there and back if the build says so. Throws what
// createJoint throws, with the body put back.
inline JointId buildJoint(World& w, const JointBuild& b) {
  if (!b.move) return w.createJoint(b.def);
  const Body& moved = w.body(b.moved);
  const Vec2 position = moved.xf.p;
  const double angle = moved.angle;
  w.setTransform(b.moved, b.position, b.angle);
  JointId id;
  try {
    id = w.createJoint(b.def);
  } catch (...) {
    w.setTransform(b.moved, position, angle);
    throw;
  }
  w.setTransform(b.moved, position, angle);
  return id;
}

}  // namespace rigidlab::lua
