// Undo/redo of edits: add, delete (with springs and dampers), property edits, moves, toggles.
#include <doctest/doctest.h>

#include "undo.h"

using namespace rigidlab;
using namespace rigidlab::sandbox;

namespace {
BodyDef box(Vec2 at, double mass = 2.0) {
  BodyDef d;
  d.shape = makeBox(1, 1);
  d.position = at;
  d.mass = mass;
  return d;
}
}  // namespace

TEST_CASE("undo: a property edit goes back and forth exactly") {
  World world;
  const BodyId id = world.createBody(box({1, 2}));
  UndoHistory h;
  const BodyProps before = captureProps(world, id);
  BodyProps after = before;
  after.mass = 7.5;
  after.shapes[0].material.restitution = 0.9;
  after.linear_damping = 0.25;
  after.gravity_scale = -1.0;
  after.bullet = true;
  after.velocity = Vec2(3, -1);
  after.position = Vec2(-4, 0.5);
  after.angle = 0.7;
  after.name = "edited";
  applyProps(world, id, after);
  const BodyProps applied = captureProps(world, id);
  h.recordModify(id, before, applied, "edit");
  CHECK(h.canUndo());
  REQUIRE(h.undo(world));
  CHECK(captureProps(world, id) == before);
  CHECK(world.body(id).mass == 2.0);
  REQUIRE(h.redo(world));
  CHECK(captureProps(world, id) == applied);
  CHECK(world.body(id).mass == 7.5);
  CHECK(world.body(id).name == "edited");
  CHECK(world.body(id).velocity.x() == 3.0);
  // Nothing recorded for a no-op edit.
  h.clear();
  h.recordModify(id, before, before, "nothing");
  CHECK_FALSE(h.canUndo());
}

TEST_CASE("undo: static/dynamic toggle keeps the velocity it had") {
  World world;
  BodyDef d = box({0, 0});
  d.velocity = Vec2(1, 2);
  const BodyId id = world.createBody(d);
  UndoHistory h;
  const BodyProps before = captureProps(world, id);
  world.setType(id, BodyType::Static);
  h.recordModify(id, before, captureProps(world, id), "make static");
  CHECK(world.body(id).velocity.norm() == 0.0);
  REQUIRE(h.undo(world));
  CHECK_FALSE(world.body(id).isStatic());
  CHECK(world.body(id).velocity.x() == 1.0);
  CHECK(world.body(id).velocity.y() == 2.0);
}

TEST_CASE("undo: delete brings the body back with its springs and dampers, edits before still apply") {
  World world;
  const BodyId a = world.createBody(box({0, 0}));
  const BodyId b = world.createBody(box({3, 0}, 5.0));
  SpringDef sd;
  sd.a = a;
  sd.b = b;
  sd.local_a = Vec2(0.5, 0);
  sd.stiffness = 40;
  sd.damping = 1.5;
  world.addSpring(sd);
  SpringDef anchor;
  anchor.a = b;
  anchor.anchor = Vec2(3, 5);
  anchor.stiffness = 10;
  world.addSpring(anchor);
  world.addDamper(DamperDef{.body = b, .coefficient = 0.3, .angular_coefficient = 0.1});

  UndoHistory h;
  const BodyProps before = captureProps(world, b);
  world.setMass(b, 9.0);
  h.recordModify(b, before, captureProps(world, b), "mass");
  h.destroy(world, b, "delete b");
  CHECK_FALSE(world.isValid(b));
  CHECK(world.forceIds().empty());  // all three went with it

  REQUIRE(h.undo(world));  // delete undone: a new handle, same body
  const BodyId b2 = h.lastTouched();
  REQUIRE(world.isValid(b2));
  CHECK(world.body(b2).mass == 9.0);
  CHECK(world.body(b2).xf.p.x() == 3.0);
  CHECK(world.forceIds().size() == 3);
  int springs = 0, dampers = 0;
  for (const ForceId f : world.forceIds()) {
    if (const auto* s = dynamic_cast<const SpringForce*>(&world.force(f))) {
      ++springs;
      if (world.forceBodyB(f).isNull()) {
        CHECK(world.forceBodyA(f) == b2);
        CHECK(s->def().anchor.y() == 5.0);
      } else {
        CHECK(world.forceBodyA(f) == a);
        CHECK(world.forceBodyB(f) == b2);
        CHECK(s->def().stiffness == 40.0);
        CHECK(s->def().damping == 1.5);
      }
    } else if (const auto* d = dynamic_cast<const DamperForce*>(&world.force(f))) {
      ++dampers;
      CHECK(d->def().coefficient == 0.3);
      CHECK(d->def().angular_coefficient == 0.1);
    }
  }
  CHECK(springs == 2);
  CHECK(dampers == 1);

  REQUIRE(h.undo(world));  // the mass edit, applied to the recreated body
  CHECK(world.body(b2).mass == 5.0);
  REQUIRE(h.redo(world));
  CHECK(world.body(b2).mass == 9.0);
  REQUIRE(h.redo(world));  // delete again
  CHECK_FALSE(world.isValid(b2));
  CHECK(world.bodyCount() == 1);
}

TEST_CASE("undo: add is undone by removing, redo adds it back as it was when undone") {
  World world;
  UndoHistory h;
  const BodyId id = world.createBody(box({0, 0}));
  h.recordCreate(world, id, "add box");
  world.setTransform(id, Vec2(2, 2), 0.5);
  REQUIRE(h.undo(world));
  CHECK(world.bodyCount() == 0);
  REQUIRE(h.redo(world));
  REQUIRE(world.bodyCount() == 1);
  const Body& b = world.body(world.bodyIds()[0]);
  CHECK(b.xf.p.x() == 2.0);
  CHECK(b.angle == 0.5);
  CHECK_FALSE(h.canRedo());
}

TEST_CASE("undo: an edit whose body a script removed is refused, not applied to another body") {
  World world;
  const BodyId a = world.createBody(box({0, 0}));
  world.createBody(box({5, 0}));
  UndoHistory h;
  const BodyProps before = captureProps(world, a);
  world.setMass(a, 4.0);
  h.recordModify(a, before, captureProps(world, a), "mass");
  world.destroyBody(a);  // behind the history's back
  CHECK_FALSE(h.undo(world));
  CHECK_FALSE(h.canUndo());
  CHECK(world.body(world.bodyIds()[0]).mass == 2.0);  // the other body is untouched
}

TEST_CASE("undo: a new edit clears the redo list, the history is bounded") {
  World world;
  const BodyId id = world.createBody(box({0, 0}));
  UndoHistory h;
  for (int i = 0; i < 3; ++i) {
    const BodyProps before = captureProps(world, id);
    world.setMass(id, 3.0 + i);
    h.recordModify(id, before, captureProps(world, id), "mass");
  }
  REQUIRE(h.undo(world));
  CHECK(h.canRedo());
  const BodyProps before = captureProps(world, id);
  world.setMass(id, 42.0);
  h.recordModify(id, before, captureProps(world, id), "mass");
  CHECK_FALSE(h.canRedo());
  for (size_t i = 0; i < UndoHistory::kMaxEdits + 50; ++i) {
    const BodyProps b = captureProps(world, id);
    world.setMass(id, 1.0 + static_cast<double>(i % 7));
    h.recordModify(id, b, captureProps(world, id), "mass");
  }
  CHECK(h.size() <= UndoHistory::kMaxEdits);
}

namespace {
JointId hinge(World& w, BodyId a, BodyId b, Vec2 at) {
  JointDef d;
  d.type = JointType::Revolute;
  d.a = a;
  d.b = b;
  d.anchor_a = at;
  d.enable_limit = true;
  d.lower = -0.5;
  d.upper = 0.25;
  d.name = "hinge";
  return w.createJoint(d);
}
}  // namespace

TEST_CASE("undo: a deleted body comes back with its joints holding it as they did, wherever the other body went") {
  World world;
  const BodyId door = world.createBody(box({0, 0}));
  const BodyId frame = world.createBody(box({1, 0}));
  const JointId j = hinge(world, frame, door, {0.5, 0});
  // The door turns 0.2 rad about the hinge and drifts a little off it.
  world.setTransform(door, Vec2(0.5, 0) + Rot::fromAngle(0.2).apply(Vec2(-0.5, 0)) + Vec2(0.001, 0), 0.2);
  const JointState before = world.jointState(j);
  UndoHistory h;
  h.destroy(world, door, "delete door");
  CHECK(world.jointIds().empty());
  // The frame moves and turns while the door is gone.
  world.setTransform(frame, Vec2(3, 1), 1.0);
  REQUIRE(h.undo(world));
  REQUIRE(world.jointIds().size() == 1);
  const JointId back = world.jointIds()[0];
  const JointDef& d = world.joint(back);
  CHECK(d.name == "hinge");
  CHECK(d.enable_limit);
  CHECK(d.lower == -0.5);
  CHECK(d.upper == 0.25);
  CHECK(d.a == frame);
  CHECK(d.b == h.lastTouched());
  // The joint holds each body at the same place of it as before: the frame's anchor moved and
  // turned with the frame, the door's is where it was (1 mm off the hinge), and the angle counts
  // from the same zero (0.2 − 1.0), so the limits are where they were on the door.
  const JointState after = world.jointState(back);
  CHECK(after.angle == doctest::Approx(0.2 - 1.0).epsilon(1e-12));
  const Transform xf{Vec2(3, 1), Rot::fromAngle(1.0)};
  CHECK((after.world_anchor_a - xf.apply(Vec2(-0.5, 0))).norm() < 1e-12);
  CHECK((after.world_anchor_b - before.world_anchor_b).norm() < 1e-12);
  REQUIRE(h.redo(world));
  CHECK(world.jointIds().empty());
}

TEST_CASE("undo: joints made, deleted and tuned go back and forth, a gear comes back with the joint it couples") {
  World world;
  const BodyId big = world.createBody(box({0, 0}));
  const BodyId small = world.createBody(box({2, 0}));
  UndoHistory h;
  const JointId pa = hinge(world, big, {}, {0, 0});
  h.recordCreateJoint(world, pa, "add a");
  const JointId pb = hinge(world, small, {}, {2, 0});
  h.recordCreateJoint(world, pb, "add b");
  JointDef g;
  g.type = JointType::Gear;
  g.joint_a = pa;
  g.joint_b = pb;
  g.ratio = 3.0;
  h.recordCreateJoint(world, world.createJoint(g), "add gear");
  CHECK(world.jointIds().size() == 3);

  // Tuning: one undo step each way.
  JointDef tuned = world.joint(pa);
  tuned.enable_motor = true;
  tuned.motor_speed = 2.0;
  tuned.max_motor_torque = 10.0;
  const JointDef old = world.joint(pa);
  world.updateJoint(pa, tuned);
  h.recordModifyJoint(pa, old, world.joint(pa), "motor");
  REQUIRE(h.undo(world));
  CHECK_FALSE(world.joint(pa).enable_motor);
  REQUIRE(h.redo(world));
  CHECK(world.joint(pa).motor_speed == 2.0);

  // Deleting a joint takes the gear on it; undo brings both back, the gear on the new joint.
  h.destroyJoint(world, pa, "delete a");
  CHECK(world.jointIds().size() == 1);
  REQUIRE(h.undo(world));
  REQUIRE(world.jointIds().size() == 3);
  int gears = 0;
  for (const JointId id : world.jointIds()) {
    const JointDef& d = world.joint(id);
    if (d.type != JointType::Gear) continue;
    ++gears;
    CHECK(d.ratio == 3.0);
    CHECK(world.isValid(d.joint_a));
    CHECK(world.joint(d.joint_a).motor_speed == 2.0);  // the tuned joint, back as it was deleted
  }
  CHECK(gears == 1);
  // Undo the tuning, then the three creations.
  REQUIRE(h.undo(world));
  for (int i = 0; i < 3; ++i) REQUIRE(h.undo(world));
  CHECK(world.jointIds().empty());
  for (int i = 0; i < 3; ++i) REQUIRE(h.redo(world));
  CHECK(world.jointIds().size() == 3);
}

TEST_CASE("undo: shape properties and body options of a compound body go back and forth") {
  World world;
  BodyDef d = box({0, 0});
  d.mass.reset();
  const BodyId id = world.createBody(d);
  ShapeDef more;
  more.shape = makeCircle(0.4, {1, 0});
  world.createShape(id, more);
  UndoHistory h;
  const BodyProps before = captureProps(world, id);
  REQUIRE(before.shapes.size() == 2);
  BodyProps after = before;
  after.type = BodyType::Kinematic;
  after.shapes[1].density = 5.0;
  after.shapes[1].sensor = true;
  after.shapes[1].filter = Filter{2, 4, -1};
  after.shapes[0].material.friction = 0.1;
  after.fixed_rotation = true;
  after.enabled = false;
  after.angular_damping = 3.0;
  applyProps(world, id, after);
  const BodyProps applied = captureProps(world, id);
  CHECK(applied.shapes[1].density == 5.0);
  CHECK(applied.mass > before.mass);  // the density edit is not undone by the mass it changed
  CHECK(world.body(id).isKinematic());
  CHECK_FALSE(world.body(id).enabled);
  h.recordModify(id, before, applied, "edit");
  REQUIRE(h.undo(world));
  CHECK(captureProps(world, id) == before);
  REQUIRE(h.redo(world));
  CHECK(captureProps(world, id) == applied);
  CHECK(world.shape(world.body(id).shapes[1]).filter == Filter{2, 4, -1});
}
