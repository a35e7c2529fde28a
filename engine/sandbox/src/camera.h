// The view's camera in metres (docs/design/thesis.md §11): the world point at the middle of the window and the
// scale in pixels per metre. Screen coordinates are pixels from the window's top-left corner, y down;
// world coordinates are metres, y up.
//
// The thesis keeps the window V metres tall whatever its size. The sandbox instead keeps the scale
// when the window is resized (the issue asks for it): a bigger window shows more of the world, and
// bodies keep their size on screen.
#pragma once

#include "rigidlab/math.h"

namespace rigidlab::sandbox {

// A rectangle of the window in pixels: `lower` its top-left corner, `upper` its bottom-right.
struct ScreenRect {
  Vec2 lower = Vec2::Zero(), upper = Vec2::Zero();
  Vec2 middle() const { return 0.5 * (lower + upper); }
  double width() const { return upper.x() - lower.x(); }
  double height() const { return upper.y() - lower.y(); }
};

struct Camera {
  Vec2 center = Vec2::Zero();   // world point at the middle of the viewport [m]
  double pixels_per_metre = 36.0;
  int width_px = 1280, height_px = 720;

  static constexpr double kMinPixelsPerMetre = 1e-3;  // a 720 px window shows 720 km
  static constexpr double kMaxPixelsPerMetre = 1e6;   // … or 0.7 mm

  double heightMetres() const { return height_px / pixels_per_metre; }
  double widthMetres() const { return width_px / pixels_per_metre; }
  // Sets the scale so the viewport is `height` metres tall.
  void setHeightMetres(double height);

  Vec2 screenToWorld(const Vec2& px) const;
  Vec2 worldToScreen(const Vec2& world) const;
  // A length on screen in metres (for line widths and point sizes given in pixels).
  double metres(double pixels) const { return pixels / pixels_per_metre; }

  // New viewport size: the centre and the scale stay.
  void resize(int width, int height);
  // Moves the view so the world follows a cursor that moved by `delta_px` (a drag).
  void pan(const Vec2& delta_px);
  // Multiplies the scale by `factor` (> 1 zooms in) keeping the world point under `px` fixed.
  void zoomAbout(const Vec2& px, double factor);
  // Centres the box and scales it to fill `fill` (0..1] of the viewport in its tighter direction.
  void fit(const Aabb& box, double fill = 0.85);
  // The same in `area`, a part of the viewport (what the panels leave free): the box's centre at
  // the area's middle, the box filling `fill` of the area.
  void fitIn(const Aabb& box, const ScreenRect& area, double fill = 0.85);
  // Moves the view (scale kept) so that the world point `world` is at pixel `px`.
  void placeAt(const Vec2& world, const Vec2& px);
};

}  // namespace rigidlab::sandbox
