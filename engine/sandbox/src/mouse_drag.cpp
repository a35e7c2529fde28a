// The mouse drag as a motor joint (mouse_drag.h).
#include "mouse_drag.h"

namespace rigidlab::sandbox {

JointId startDrag(World& world, BodyId body, const Vec2& grab) {
  const Body& b = world.body(body);
  JointDef d;
  d.type = JointType::Motor;
  d.b = body;  // a: the world, so the offset is the target in world coordinates
  d.anchor_a = grab;
  d.use_offsets = true;
  d.linear_offset = grab;
  d.angular_offset = b.angle;
  d.motor_hertz = kDragHertz;
  d.motor_damping = kDragDamping;
  // In weights of standard gravity, not the scene's: a pull works in a world without gravity too.
  d.max_force = kDragWeights * b.mass * 9.80665;
  d.max_torque = 0.0;
  return world.createJoint(d);
}

void moveDrag(World& world, JointId drag, const Vec2& target) {
  JointDef d = world.joint(drag);
  if (d.linear_offset == target) return;  // updateJoint wakes the body: only when the cursor moved
  d.linear_offset = target;
  world.updateJoint(drag, d);
}

DragLine dragLine(const World& world, JointId drag) {
  return {world.jointState(drag).world_anchor_b, world.joint(drag).linear_offset};
}

}  // namespace rigidlab::sandbox
