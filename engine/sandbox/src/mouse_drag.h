// Pulling a body with the mouse while the world runs: a motor joint between the world and the
// body (JointType::Motor), its target moved with the cursor. Being a joint, the pull is solved with
// the contacts, so a dragged body pushes a pile without sinking into it and stops where the cursor
// stops; the force is capped so it cannot throw other bodies around.
#pragma once

#include "rigidlab/world.h"

namespace rigidlab::sandbox {

// The spring of the pull (motor_hertz, motor_damping) and its force cap in the body's weights.
inline constexpr double kDragHertz = 5.0, kDragDamping = 0.7, kDragWeights = 100.0;

// A motor joint holding the point `grab` of `body` (dynamic) at the target `grab`; turning is left
// free (no torque). Throws what World::createJoint throws.
JointId startDrag(World& world, BodyId body, const Vec2& grab);
// Moves the target to `target` [m, world].
void moveDrag(World& world, JointId drag, const Vec2& target);
// The grabbed point and the target, for drawing.
struct DragLine {
  Vec2 grabbed, target;
};
DragLine dragLine(const World& world, JointId drag);

}  // namespace rigidlab::sandbox
