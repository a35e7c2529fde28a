// The joint tool (joint_tool.h).
#include "joint_tool.h"

#include <cmath>
#include <numbers>

#include "picking.h"
#include "renderer.h"

namespace rigidlab::sandbox {

namespace {
constexpr double kPickPixels = 6.0;  // segments and chains are picked this close
}

JointDef toolJointDef(const ToolState& t, BodyId a, const Vec2& p1, BodyId b, const Vec2& p2) {
  JointDef d;
  d.type = t.joint_kind;
  // Pinned to the world (b null), the world is the joint's body a, as Box2D and the scene API
  // (a saved world reopens as the same joints) have it.
  const bool pinned = b.isNull();
  d.a = pinned ? BodyId{} : a;
  d.b = pinned ? a : b;
  d.collide_connected = t.joint_collide;
  d.anchor_a = p2;
  const double axis = t.joint_axis_degrees * std::numbers::pi / 180.0;
  switch (t.joint_kind) {
    case JointType::Distance:
      d.anchor_a = pinned ? p2 : p1;
      d.anchor_b = pinned ? p1 : p2;
      if (t.joint_rope) {  // slack below its length, taut at it
        d.enable_limit = true;
        d.min_length = 0.0;
        d.max_length = (p2 - p1).norm();
      }
      break;
    case JointType::Prismatic:
      d.axis = Vec2(std::cos(axis), std::sin(axis));
      break;
    case JointType::Wheel:  // a suspension: the spring of a small car's wheel
      d.axis = Vec2(std::cos(axis), std::sin(axis));
      d.enable_spring = true;
      d.spring_hertz = 4.0;
      d.spring_damping = 0.7;
      break;
    default:
      break;
  }
  return d;
}

void pressJointTool(Session& s, const Vec2& p) {
  ToolState& t = s.tools;
  World& w = s.world();
  const double tolerance = s.camera.metres(kPickPixels);
  if (!w.isValid(t.joint_body)) {
    t.joint_body = {};
    const auto hit = pickBody(w, p, tolerance);
    if (!hit) {
      s.setStatus("joint tool: click a body first, then where the joint goes");
      return;
    }
    t.joint_body = *hit;
    t.joint_point = p;
    select(s, *hit);
    s.setStatus("now click where the joint goes: on another body, or on empty space to pin it to the world", 6.0);
    return;
  }
  const BodyId a = t.joint_body;
  const BodyId b = pickBody(w, p, tolerance, a).value_or(BodyId{});
  t.joint_body = {};
  const std::string label = std::string("add ") + jointTypeName(t.joint_kind) + " joint";
  if (!addJoint(s, toolJointDef(t, a, t.joint_point, b, p), label).isNull())
    s.setStatus(label + (b.isNull() ? " to the world" : " between two bodies"));
}

void drawJointToolOverlay(const Session& s, Renderer& r, const Vec2& cursor) {
  const ToolState& t = s.tools;
  if (!s.world().isValid(t.joint_body)) return;
  r.drawSegment(t.joint_point, cursor, Palette::preview);
  r.drawPoint(t.joint_point, 7.0f, Palette::preview);
  r.drawPoint(cursor, 7.0f, Palette::preview);
}

}  // namespace rigidlab::sandbox
