// Drawing the world through the DebugDraw interface (the sandbox implements it with OpenGL).
#include "rigidlab/debug_draw.h"

#include <algorithm>
#include <cmath>

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
