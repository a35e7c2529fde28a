// The default drawing of OverlayDraw's filled shapes (scene.h): outlines through line() and
// circle(), for drawers that only count or record what a scene draws.
#include "rigidlab/lua/scene.h"

namespace rigidlab::lua {

void OverlayDraw::polygon(std::span<const Vec2> points, const Color& color, const std::optional<Color>&) {
  for (size_t i = 0; i < points.size(); ++i) line(points[i], points[(i + 1) % points.size()], color);
}

void OverlayDraw::capsule(const Vec2& a, const Vec2& b, double radius, const Color& color, const std::optional<Color>&) {
  const Vec2 d = b - a;
  const double length = d.norm();
  const Vec2 side = length > 0.0 ? Vec2(-d.y(), d.x()) * (radius / length) : Vec2(0.0, radius);
  line(a + side, b + side, color);
  line(a - side, b - side, color);
  circle(a, radius, color);
  circle(b, radius, color);
}

void OverlayDraw::disc(const Vec2& center, double radius, const Color& color, const Color&) { circle(center, radius, color); }

}  // namespace rigidlab::lua
