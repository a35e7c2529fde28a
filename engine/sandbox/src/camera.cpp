// Camera maths: screen ↔ world, pan, zoom about the cursor, fit (camera.h).
#include "camera.h"

#include <algorithm>

namespace rigidlab::sandbox {

void Camera::setHeightMetres(double height) {
  if (!(height > 0.0) || !std::isfinite(height)) return;
  pixels_per_metre = std::clamp(height_px / height, kMinPixelsPerMetre, kMaxPixelsPerMetre);
}

// x_world = c_x + (x_px − W/2) / s,   y_world = c_y − (y_px − H/2) / s   (s = pixels per metre)
Vec2 Camera::screenToWorld(const Vec2& px) const {
  return Vec2(center.x() + (px.x() - 0.5 * width_px) / pixels_per_metre,
              center.y() - (px.y() - 0.5 * height_px) / pixels_per_metre);
}

Vec2 Camera::worldToScreen(const Vec2& world) const {
  return Vec2(0.5 * width_px + (world.x() - center.x()) * pixels_per_metre,
              0.5 * height_px - (world.y() - center.y()) * pixels_per_metre);
}

void Camera::resize(int width, int height) {
  width_px = std::max(width, 1);
  height_px = std::max(height, 1);
}

void Camera::pan(const Vec2& delta_px) {
  center += Vec2(-delta_px.x(), delta_px.y()) / pixels_per_metre;
}

void Camera::zoomAbout(const Vec2& px, double factor) {
  if (!(factor > 0.0) || !std::isfinite(factor)) return;
  const Vec2 anchor = screenToWorld(px);
  pixels_per_metre = std::clamp(pixels_per_metre * factor, kMinPixelsPerMetre, kMaxPixelsPerMetre);
  // Put the anchor back under the cursor: c = anchor − (screenToWorld(px) − c).
  center += anchor - screenToWorld(px);
}

void Camera::fit(const Aabb& box, double fill) {
  fitIn(box, ScreenRect{Vec2::Zero(), Vec2(width_px, height_px)}, fill);
}

void Camera::fitIn(const Aabb& box, const ScreenRect& area, double fill) {
  const Vec2 size = box.upper - box.lower;
  if (!isFinite(box.lower) || !isFinite(box.upper) || size.x() < 0 || size.y() < 0) return;
  if (!(area.width() > 0.0) || !(area.height() > 0.0)) return;
  // A point or a line still gets a sensible scale: at least 1 m of world on screen.
  const double sx = std::max(size.x(), 1.0), sy = std::max(size.y(), 1.0);
  const double scale = fill * std::min(area.width() / sx, area.height() / sy);
  pixels_per_metre = std::clamp(scale, kMinPixelsPerMetre, kMaxPixelsPerMetre);
  placeAt(0.5 * (box.lower + box.upper), area.middle());
}

// From screenToWorld(px) = world: c_x = w_x − (px_x − W/2) / s, c_y = w_y + (px_y − H/2) / s.
void Camera::placeAt(const Vec2& world, const Vec2& px) {
  center = Vec2(world.x() - (px.x() - 0.5 * width_px) / pixels_per_metre,
                world.y() + (px.y() - 0.5 * height_px) / pixels_per_metre);
}

}  // namespace rigidlab::sandbox
