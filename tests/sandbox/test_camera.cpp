// Camera maths: metres ↔ pixels, pan, zoom about the cursor, resize keeps the scale, fit.
#include <doctest/doctest.h>

#include "camera.h"

using namespace rigidlab;
using namespace rigidlab::sandbox;

namespace {
Camera camera1280() {
  Camera c;
  c.resize(1280, 720);
  c.center = Vec2(0, 0);
  c.setHeightMetres(10.0);  // 72 px per metre
  return c;
}
}  // namespace

TEST_CASE("camera: a 10 m tall view of 720 px maps metres to pixels, y up") {
  const Camera c = camera1280();
  CHECK(c.pixels_per_metre == doctest::Approx(72.0));
  const Vec2 centre = c.worldToScreen(Vec2(0, 0));
  CHECK(centre.x() == doctest::Approx(640));
  CHECK(centre.y() == doctest::Approx(360));
  const Vec2 p = c.worldToScreen(Vec2(2, 1));
  CHECK(p.x() == doctest::Approx(640 + 144));
  CHECK(p.y() == doctest::Approx(360 - 72));  // up in the world is up on screen
  const Vec2 back = c.screenToWorld(p);
  CHECK(back.x() == doctest::Approx(2));
  CHECK(back.y() == doctest::Approx(1));
}

TEST_CASE("camera: zoom keeps the world point under the cursor in place") {
  Camera c = camera1280();
  const Vec2 cursor(1000, 100);
  const Vec2 before = c.screenToWorld(cursor);
  c.zoomAbout(cursor, 1.7);
  CHECK(c.pixels_per_metre == doctest::Approx(72 * 1.7));
  const Vec2 after = c.screenToWorld(cursor);
  CHECK(after.x() == doctest::Approx(before.x()).epsilon(1e-12));
  CHECK(after.y() == doctest::Approx(before.y()).epsilon(1e-12));
  c.zoomAbout(cursor, 1e30);  // clamped, still finite
  CHECK(c.pixels_per_metre == Camera::kMaxPixelsPerMetre);
  CHECK(isFinite(c.center));
}

TEST_CASE("camera: a drag pans the world with the cursor") {
  Camera c = camera1280();
  const Vec2 grabbed = c.screenToWorld(Vec2(300, 200));
  c.pan(Vec2(50, -30));  // the cursor moved right and up
  const Vec2 now = c.worldToScreen(grabbed);
  CHECK(now.x() == doctest::Approx(350));
  CHECK(now.y() == doctest::Approx(170));
}

TEST_CASE("camera: a resize keeps the scale and the centre") {
  Camera c = camera1280();
  c.center = Vec2(3, -4);
  c.resize(640, 480);
  CHECK(c.pixels_per_metre == doctest::Approx(72.0));
  CHECK(c.heightMetres() == doctest::Approx(480.0 / 72.0));
  const Vec2 m = c.worldToScreen(Vec2(3, -4));
  CHECK(m.x() == doctest::Approx(320));
  CHECK(m.y() == doctest::Approx(240));
}

TEST_CASE("camera: fit puts the box in the middle, inside the view") {
  Camera c = camera1280();
  c.fit(Aabb{Vec2(10, 0), Vec2(30, 5)}, 0.8);
  CHECK(c.center.x() == doctest::Approx(20));
  CHECK(c.center.y() == doctest::Approx(2.5));
  // 20 m wide in 1280 px at 80 %: 51.2 px/m; 5 m tall would allow more, so width decides.
  CHECK(c.pixels_per_metre == doctest::Approx(0.8 * 1280 / 20.0));
  const Vec2 lo = c.worldToScreen(Vec2(10, 0)), hi = c.worldToScreen(Vec2(30, 5));
  CHECK(lo.x() >= 0);
  CHECK(hi.x() <= 1280);
  CHECK(hi.y() >= 0);
  CHECK(lo.y() <= 720);
  // A single point gets a sensible, finite view.
  c.fit(Aabb{Vec2(1, 1), Vec2(1, 1)});
  CHECK(std::isfinite(c.pixels_per_metre));
  CHECK(c.center.x() == doctest::Approx(1));
}
