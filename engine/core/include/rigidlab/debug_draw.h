// The drawing interface the core talks to. The sandbox implements it with OpenGL; the core never
// calls a graphics API. Coordinates are world metres.
#pragma once

#include <span>

#include "rigidlab/math.h"

namespace rigidlab {

struct Color {
  float r = 1, g = 1, b = 1, a = 1;
};

class DebugDraw {
 public:
  virtual ~DebugDraw() = default;

  virtual void drawPolygon(std::span<const Vec2> vertices, const Color& fill, const Color& outline) = 0;
  // A disc with a radius line at `angle`, so rotation is visible.
  virtual void drawCircle(const Vec2& center, double radius, double angle, const Color& fill, const Color& outline) = 0;
  virtual void drawSegment(const Vec2& a, const Vec2& b, const Color& color) = 0;
  virtual void drawPoint(const Vec2& p, float size_pixels, const Color& color) = 0;

  // Composite shapes built from the primitives above; an implementation may override them.
  // A capsule: the points within `radius` of the segment a–b (drawn as a 2 × 12-cornered outline).
  virtual void drawCapsule(const Vec2& a, const Vec2& b, double radius, const Color& fill, const Color& outline);
  virtual void drawSpring(const Vec2& a, const Vec2& b, double width, const Color& color);
  virtual void drawArrow(const Vec2& from, const Vec2& to, const Color& color);
};

// A force drawn as an arrow from its application point, 1 m long per the body's weight (m·g0),
// clamped to 0.2–3 m so small and large forces stay readable. Nothing for a zero force.
void drawForceArrow(DebugDraw& dd, const Vec2& from, const Vec2& force, double mass);

}  // namespace rigidlab
