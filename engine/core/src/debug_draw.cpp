// Drawing the world through the DebugDraw interface (the sandbox implements it with OpenGL).
#include "rigidlab/debug_draw.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "world_impl.h"

namespace rigidlab {

void DebugDraw::drawSpring(const Vec2& a, const Vec2& b, double width, const Color& color) {
  // A zigzag with straight ends; the number of coils is fixed so a stretched spring looks stretched.
  const Vec2 d = b - a;
  const double length = d.norm();
  if (length == 0.0) return;
  const Vec2 u = d / length, side = perp(u) * (0.5 * width);
  constexpr int kCoils = 8;
  const double lead = 0.1 * length;
  Vec2 prev = a + u * lead;
  drawSegment(a, prev, color);
  for (int i = 0; i < 2 * kCoils; ++i) {
    const double s = lead + (length - 2 * lead) * (i + 0.5) / (2 * kCoils);
    const Vec2 p = a + u * s + (i % 2 == 0 ? side : Vec2(-side));
    drawSegment(prev, p, color);
    prev = p;
  }
  const Vec2 end = b - u * lead;
  drawSegment(prev, end, color);
  drawSegment(end, b, color);
}

void DebugDraw::drawCapsule(const Vec2& a, const Vec2& b, double radius, const Color& fill, const Color& outline) {
  const Vec2 d = b - a;
  const double length = d.norm();
  const Vec2 u = length > 0.0 ? Vec2(d / length) : Vec2(1.0, 0.0);
  const double base = std::atan2(u.y(), u.x());
  constexpr int kHalf = 12;  // corners per half circle
  std::vector<Vec2> outline_points;
  for (int i = 0; i <= kHalf; ++i) {  // around b from −90° to +90°, then around a
    const double t = base - M_PI / 2 + M_PI * i / kHalf;
    outline_points.push_back(b + radius * Vec2(std::cos(t), std::sin(t)));
  }
  for (int i = 0; i <= kHalf; ++i) {
    const double t = base + M_PI / 2 + M_PI * i / kHalf;
    outline_points.push_back(a + radius * Vec2(std::cos(t), std::sin(t)));
  }
  drawPolygon(outline_points, fill, outline);
}

void DebugDraw::drawArrow(const Vec2& from, const Vec2& to, const Color& color) {
  drawSegment(from, to, color);
  const Vec2 d = to - from;
  const double length = d.norm();
  if (length == 0.0) return;
  const Vec2 u = d / length;
  const double head = std::min(0.25, 0.3 * length);
  drawSegment(to, to - head * u + 0.5 * head * perp(u), color);
  drawSegment(to, to - head * u - 0.5 * head * perp(u), color);
}

void drawForceArrow(DebugDraw& dd, const Vec2& from, const Vec2& force, double mass) {
  const double magnitude = force.norm();
  if (magnitude == 0.0) return;
  const double weight = std::max(mass * 9.80665, 1e-12);
  const double length = std::clamp(magnitude / weight, 0.2, 3.0);
  dd.drawArrow(from, from + force / magnitude * length, {1.0f, 0.4f, 0.3f, 1.0f});
}

namespace {

// A joint's frames at the drawn poses: where its anchors are, and where its bodies' centres are.
struct JointPose {
  Transform xa, xb;
  Vec2 anchor_a, anchor_b;
  std::optional<Vec2> center_a, center_b;  // nothing for the world
  double angle_a = 0.0, angle_b = 0.0;
};

// The colour of a joint kind's lines (each kind its own, as Box2D's debug draw has them).
Color jointColor(JointType type) {
  switch (type) {
    case JointType::Revolute: return {0.55f, 0.95f, 0.75f, 0.9f};   // sea green
    case JointType::Prismatic: return {0.45f, 0.75f, 1.0f, 0.9f};   // sky blue
    case JointType::Distance: return {0.95f, 0.85f, 0.45f, 0.9f};   // straw
    case JointType::Weld: return {0.9f, 0.6f, 0.95f, 0.9f};         // orchid
    case JointType::Wheel: return {0.5f, 0.9f, 0.95f, 0.9f};        // turquoise
    case JointType::Motor: return {1.0f, 0.65f, 0.75f, 0.9f};       // pink
    case JointType::Friction: return {0.8f, 0.8f, 0.6f, 0.9f};      // khaki
    case JointType::Pulley: return {0.75f, 0.7f, 1.0f, 0.9f};       // lavender
    case JointType::Gear: return {0.95f, 0.75f, 0.5f, 0.9f};        // tan
  }
  return {0.8f, 0.8f, 0.8f, 0.9f};
}

// Joints as lines, each kind in its colour (no allocation): the bodies' centres joined to their
// anchors and the anchors to each other (as Box2D's debug draw does), the anchors as points, and
// what each kind constrains: a ring at a revolute pin, a square at a weld, prismatic and wheel
// axes, a distance joint as a line or a spring, pulley ropes, the two geared bodies joined. Limits
// are drawn where the line from the anchor to b's centre would point (revolute) or where b's
// anchor would be (prismatic, wheel) at the bounds.
template <typename TransformOf>
void drawJoints(const WorldImpl& w, DebugDraw& dd, TransformOf transformOf) {
  const Color anchor{0.7f, 1.0f, 0.85f, 1.0f}, limit{1.0f, 0.6f, 0.3f, 1.0f}, gap{1.0f, 0.3f, 0.3f, 1.0f};
  const Color none{0.0f, 0.0f, 0.0f, 0.0f};
  const auto size = [&](uint32_t slot) {  // a length for marks on a body: about its size, 0.1 to 1 m
    return slot == kWorldSlot ? 0.5 : std::clamp(w.bodies[slot].max_extent, 0.1, 1.0);
  };
  for (const Joint& j : w.joints) {
    if (!j.alive) continue;
    const Color line = jointColor(j.def.type);
    JointPose p;
    const auto place = [&](uint32_t slot, Transform& xf, std::optional<Vec2>& center, double& angle) {
      if (slot == kWorldSlot) return;
      xf = transformOf(slot);
      center = xf.apply(w.bodies[slot].local_center);
      angle = std::atan2(xf.q.s, xf.q.c);
    };
    place(j.a, p.xa, p.center_a, p.angle_a);
    place(j.b, p.xb, p.center_b, p.angle_b);
    if (j.def.type == JointType::Gear) {  // the two geared bodies
      if (p.center_a && p.center_b) dd.drawSegment(*p.center_a, *p.center_b, line);
      continue;
    }
    p.anchor_a = p.xa.apply(j.local_a);
    p.anchor_b = p.xb.apply(j.local_b);
    if (p.center_a) dd.drawSegment(*p.center_a, p.anchor_a, line);
    if (p.center_b) dd.drawSegment(*p.center_b, p.anchor_b, line);
    const double mark = 0.25 * std::min(size(j.a), size(j.b));  // a ring's radius, a square's half side
    switch (j.def.type) {
      case JointType::Distance:
        if (j.def.enable_spring && j.def.spring_hertz > 0.0)
          dd.drawSpring(p.anchor_a, p.anchor_b, 0.15 * std::min(size(j.a), size(j.b)), line);
        else
          dd.drawSegment(p.anchor_a, p.anchor_b, line);
        break;
      case JointType::Motor:     // b's anchor and its target
      case JointType::Friction:  // the anchors, which the joint holds together by friction
        dd.drawSegment(p.anchor_a, p.anchor_b, line);
        break;
      case JointType::Pulley:
        dd.drawSegment(p.anchor_a, j.def.ground_a, line);
        dd.drawSegment(j.def.ground_a, j.def.ground_b, line);
        dd.drawSegment(j.def.ground_b, p.anchor_b, line);
        dd.drawPoint(j.def.ground_a, 6.0f, anchor);
        dd.drawPoint(j.def.ground_b, 6.0f, anchor);
        break;
      case JointType::Prismatic:
      case JointType::Wheel: {
        const Vec2 u = p.xa.q.apply(j.local_axis), n = perp(u);
        const double reach = 2.0 * size(j.b);
        dd.drawSegment(p.anchor_a - reach * u, p.anchor_a + reach * u, line);
        dd.drawSegment(p.anchor_a, p.anchor_b, line);  // how far b has slid along the axis
        if (j.def.type == JointType::Wheel) dd.drawCircle(p.anchor_b, mark, 0.0, none, line);
        if (j.def.enable_limit) {
          const double tick = 0.3 * size(j.b);
          for (const double bound : {j.def.lower, j.def.upper}) {
            const Vec2 at = p.anchor_a + bound * u;
            dd.drawSegment(at - tick * n, at + tick * n, limit);
          }
        }
        break;
      }
      case JointType::Revolute:
        dd.drawCircle(p.anchor_b, mark, p.angle_b, none, line);  // the pin, its radius line turning with b
        if (j.def.enable_limit) {
          const Vec2 arm = p.center_b ? Vec2(*p.center_b - p.anchor_b) : Vec2::Zero();
          const double current = p.angle_b - p.angle_a - j.reference_angle;
          const double direction = arm.norm() > 1e-9 ? std::atan2(arm.y(), arm.x()) : p.angle_b;
          const double length = std::clamp(arm.norm(), 0.5 * size(j.b), 2.0 * size(j.b));
          for (const double bound : {j.def.lower, j.def.upper}) {
            const double t = direction + bound - current;
            dd.drawSegment(p.anchor_b, p.anchor_b + length * Vec2(std::cos(t), std::sin(t)), limit);
          }
        }
        break;
      case JointType::Weld: {
        const Rot q = Rot::fromAngle(p.angle_b);
        const Vec2 corners[4] = {p.anchor_b + q.apply(Vec2(-mark, -mark)), p.anchor_b + q.apply(Vec2(mark, -mark)),
                                 p.anchor_b + q.apply(Vec2(mark, mark)), p.anchor_b + q.apply(Vec2(-mark, mark))};
        dd.drawPolygon(corners, none, line);
        break;
      }
      default:
        break;
    }
    // Anchors that should coincide and do not (a joint pulled apart) are joined in red.
    const bool one_anchor = j.def.type == JointType::Revolute || j.def.type == JointType::Weld;
    if (one_anchor && (p.anchor_b - p.anchor_a).norm() > 1e-3) dd.drawSegment(p.anchor_a, p.anchor_b, gap);
    dd.drawPoint(p.anchor_a, 6.0f, anchor);
    dd.drawPoint(p.anchor_b, 6.0f, anchor);
  }
}

}  // namespace

void World::draw(DebugDraw& dd, const DrawOptions& opt) const {
  const WorldImpl& w = *impl_;
  const Color static_fill{0.35f, 0.38f, 0.42f, 1.0f}, static_line{0.6f, 0.65f, 0.7f, 1.0f};
  const Color dynamic_fill{0.25f, 0.45f, 0.75f, 0.8f}, dynamic_line{0.75f, 0.85f, 1.0f, 1.0f};
  const Color selected_line{1.0f, 0.85f, 0.2f, 1.0f};
  const Color frozen_fill{0.7f, 0.2f, 0.6f, 0.8f};  // stopped by the NaN firewall
  const Color sleeping_fill{0.18f, 0.28f, 0.42f, 0.8f};  // asleep: a darker blue
  const auto transformOf = [&](size_t i) {
    return i < opt.transforms.size() ? opt.transforms[i] : w.bodies[i].xf;
  };

  const Color kinematic_fill{0.55f, 0.42f, 0.2f, 0.85f}, kinematic_line{1.0f, 0.8f, 0.45f, 1.0f};  // amber
  const Color disabled_line{0.45f, 0.45f, 0.45f, 0.6f};
  std::vector<Vec2> poly;
  for (size_t i = 0; i < w.bodies.size(); ++i) {
    if (!w.alive[i]) continue;
    const Body& b = w.bodies[i];
    const Transform xf = transformOf(i);
    const bool selected = b.id == opt.selected;
    const Color& body_fill = b.frozen ? frozen_fill
                             : b.isStatic() ? static_fill
                             : b.isKinematic() ? kinematic_fill
                             : b.awake ? dynamic_fill
                                       : sleeping_fill;
    const Color& body_line = selected        ? selected_line
                             : !b.enabled    ? disabled_line
                             : b.isStatic()  ? static_line
                             : b.isKinematic() ? kinematic_line
                                             : dynamic_line;
    for (ShapeId id : b.shapes) {
      const BodyShape& s = w.shapes[id.index];
      const Shape& shape = s.geometry;
      // Sensors and disabled bodies: outline only.
      const Color fill = s.sensor || !b.enabled ? Color{body_fill.r, body_fill.g, body_fill.b, 0.15f} : body_fill;
      if (opt.shapes) {
        switch (shape.type) {
          case ShapeType::Circle:
            dd.drawCircle(xf.apply(shape.center), shape.radius, std::atan2(xf.q.s, xf.q.c), fill, body_line);
            break;
          case ShapeType::Polygon:
            poly.clear();
            for (const Vec2& v : shape.vertices) poly.push_back(xf.apply(v));
            dd.drawPolygon(poly, fill, body_line);
            break;
          case ShapeType::Capsule:
            dd.drawCapsule(xf.apply(shape.vertices[0]), xf.apply(shape.vertices[1]), shape.radius, fill, body_line);
            break;
          case ShapeType::Segment:
          case ShapeType::ChainSegment: {
            const Vec2 p = xf.apply(shape.vertices[0]), q = xf.apply(shape.vertices[1]);
            dd.drawSegment(p, q, body_line);
            if (shape.type == ShapeType::ChainSegment) {  // a tick on the solid side's back: one-sided
              const Vec2 mid = 0.5 * (p + q), n = xf.q.apply(shape.normals[0]);
              dd.drawSegment(mid, mid - 0.05 * (q - p).norm() * n, body_line);
            }
            break;
          }
        }
      }
      if (opt.aabbs) {
        const Aabb box = computeAabb(shape, xf);
        const Color c{0.8f, 0.3f, 0.8f, 1.0f};
        const Vec2 lr(box.upper.x(), box.lower.y()), ul(box.lower.x(), box.upper.y());
        dd.drawSegment(box.lower, lr, c);
        dd.drawSegment(lr, box.upper, c);
        dd.drawSegment(box.upper, ul, c);
        dd.drawSegment(ul, box.lower, c);
      }
    }
    const Vec2 center = xf.apply(b.local_center);
    if (opt.centers) dd.drawPoint(center, 5.0f, {1.0f, 1.0f, 1.0f, 1.0f});
    if (opt.velocities && !b.isStatic())
      dd.drawArrow(center, center + b.velocity * 0.25, {0.3f, 1.0f, 0.5f, 1.0f});  // 0.25 s of travel
  }

  if (opt.joints) drawJoints(w, dd, transformOf);

  for (const ForceEntry& f : w.forces) {
    if (!f.alive) continue;
    const bool is_spring = f.force->kind() == "spring";
    if ((is_spring && !opt.springs) || (!is_spring && !opt.forces)) continue;
    const BodyState a = WorldImpl::stateOf(w.bodies[f.a.index]);
    if (f.b.isNull()) {
      f.force->draw(dd, a, nullptr);
    } else {
      const BodyState b = WorldImpl::stateOf(w.bodies[f.b.index]);
      f.force->draw(dd, a, &b);
    }
  }

  if (opt.contacts || opt.normals || opt.impulses) {
    for (const Contact& c : w.contacts) {
      for (int i = 0; i < c.count; ++i) {
        const ContactPoint& cp = c.points[i];
        if (opt.contacts) dd.drawPoint(cp.point, 6.0f, {1.0f, 0.3f, 0.3f, 1.0f});
        if (opt.normals) dd.drawArrow(cp.point, cp.point + 0.3 * c.normal, {1.0f, 1.0f, 0.4f, 1.0f});
        // Impulse drawn as the momentum change of a 1 kg body: 1 m per 1 N·s.
        if (opt.impulses) dd.drawSegment(cp.point, cp.point + cp.normal_impulse * c.normal, {1.0f, 0.6f, 0.2f, 1.0f});
      }
    }
  }
}

}  // namespace rigidlab
