// The joint tool: two clicks join two bodies, or a body and the world.
//   1. click a body: the joint's body a (and, for a distance joint, its anchor on a);
//   2. click where the joint goes: on another body, that body is b; on empty space (or on a
//      again), b is the world. That point is the anchor (a distance joint's anchor on b).
// The kind (revolute, weld, distance, prismatic, wheel) and its options are chosen in the panel;
// the new joint is selected, so its fields are at hand in the Joint panel.
#pragma once

#include "session.h"

namespace rigidlab::sandbox {

class Renderer;

// A left click of the joint tool at world point `p`.
void pressJointTool(Session& s, const Vec2& p);
// The definition the tool makes: kind and options from `t`, body a clicked at p1, body b (null:
// the world) clicked at p2.
JointDef toolJointDef(const ToolState& t, BodyId a, const Vec2& p1, BodyId b, const Vec2& p2);
// The first click and the line to the cursor.
void drawJointToolOverlay(const Session& s, Renderer& r, const Vec2& cursor);

}  // namespace rigidlab::sandbox
