// The camera following a body (camera_follow.h; scene.camera.follow, the C key, a pan), a scene's own
// view framed in the part of the window the panels leave free (session.cpp placeCamera), and the
// step stages recorded for the Profile panel as the session steps.
#include <doctest/doctest.h>

#include <string>

#include "camera_follow.h"
#include "panel_layout.h"
#include "session_helpers.h"

using namespace rigidlab;
using namespace rigidlab::sandbox;
using namespace rigidlab::sandbox::testing;

namespace {

// A ball thrown along the ground; the scene follows it (given as `follow`, a Lua expression).
std::string thrownBall(const std::string& follow) {
  return "scene = { gravity = {0, 0}, camera = { center = {0, 0}, height = 10 } }\n"
         "function PopulateWorld(world)\n"
         "  local ball = world:add_circle{ name = 'ball', radius = 0.5, velocity = {6, 0} }\n"
         "  world:add_box{ name = 'wall', width = 1, height = 4, position = {-3, 0}, static = true }\n"
         "  scene.camera.follow = " + follow + "\n"
         "end\n";
}

// Runs `frames` frames of 1/60 s as the sandbox's loop does: steps, then the camera.
void frames(Session& s, int frames) {
  for (int i = 0; i < frames; ++i) {
    advance(s, 1.0 / 60.0);
    updateFollow(s);
  }
}

Vec2 freeMiddle(const Session& s) { return freeViewArea(s.camera.width_px, s.camera.height_px, s.show_panels).middle(); }

}  // namespace

TEST_CASE("camera follow: scene.camera.follow keeps the body at the middle of the free area, by handle or by name") {
  for (const std::string follow : {"ball", "'ball'"}) {
    CAPTURE(follow);
    TempDir dir;
    Session s;
    startOn(s, dir.path / "thrown.lua", thrownBall(follow));
    REQUIRE(s.scene_loaded);
    const BodyId ball = *s.world().findBody(std::string_view("ball"));
    CHECK(s.follow == ball);
    const double scale = s.camera.pixels_per_metre;
    frames(s, 120);  // 2 s at 6 m/s: 12 m, past the 10 m the window shows
    const Vec2 at = s.camera.worldToScreen(drawnCenter(s, ball));
    CHECK(at.x() == doctest::Approx(freeMiddle(s).x()));
    CHECK(at.y() == doctest::Approx(freeMiddle(s).y()));
    CHECK(s.world().body(ball).center.x() > 11.0);
    CHECK(s.camera.pixels_per_metre == scale);  // the zoom is the user's
  }
}

TEST_CASE("camera follow: a pan or F stops it, C follows the selected body and stops again") {
  TempDir dir;
  Session s;
  startOn(s, dir.path / "thrown.lua", thrownBall("ball"));
  REQUIRE(s.scene_loaded);
  const BodyId ball = *s.world().findBody(std::string_view("ball"));
  handleEvent(s, key(SDLK_LEFT), {});  // a pan
  CHECK(s.follow.isNull());
  const Vec2 center = s.camera.center;
  frames(s, 30);
  CHECK(s.camera.center == center);  // the camera stays where the user put it
  select(s, ball);
  handleEvent(s, key(SDLK_c), {});
  CHECK(s.follow == ball);
  frames(s, 1);
  CHECK(s.camera.worldToScreen(drawnCenter(s, ball)).x() == doctest::Approx(freeMiddle(s).x()));
  handleEvent(s, key(SDLK_c), {});
  CHECK(s.follow.isNull());
  handleEvent(s, key(SDLK_c), {});
  CHECK(s.follow == ball);
  handleEvent(s, key(SDLK_f), {});  // Fit: the whole scene
  CHECK(s.follow.isNull());
  select(s, {});
  handleEvent(s, key(SDLK_c), {});  // nothing selected: nothing to follow
  CHECK(s.follow.isNull());
  // A followed body that goes away ends the following.
  select(s, ball);
  handleEvent(s, key(SDLK_c), {});
  deleteBody(s, ball);
  frames(s, 1);
  CHECK(s.follow.isNull());
}

TEST_CASE("camera follow: a bad scene.camera.follow is an error naming the field") {
  TempDir dir;
  const auto error = [&](const std::string& follow) {
    Session s;
    startOn(s, dir.path / "bad.lua", thrownBall(follow));
    CHECK_FALSE(s.scene_loaded);
    return s.load_error;
  };
  CHECK(error("5").find("scene.camera: follow must be a body or a body's name, got 5") != std::string::npos);
  CHECK(error("'nobody'").find("scene.camera: follow names no body: \"nobody\"") != std::string::npos);
  Session s;
  startOn(s, dir.path / "typo.lua", "scene = { camera = { folow = 'x' } }\nfunction PopulateWorld(world) end\n");
  CHECK(s.load_error.find("unknown option 'folow' (did you mean 'follow'?)") != std::string::npos);
}

TEST_CASE("framing: a scene's own view shows its moving bodies between the panels, zooming out only for them") {
  TempDir dir;
  const auto open = [&](const std::string& bodies) {
    auto s = std::make_unique<Session>();
    startOn(*s, dir.path / "view.lua",
            "scene = { gravity = {0, 0}, camera = { center = {0, 0}, height = 10 } }\n"
            "function PopulateWorld(world)\n"
            "  world:add_box{ width = 60, height = 1, position = {0, -4}, static = true }\n" +
                bodies + "end\n");
    REQUIRE(s->scene_loaded);
    return s;
  };
  const ScreenRect area = freeViewArea(1280, 720, true);
  // Bodies inside the free area (and the long static ground): the scene's view as given.
  auto plain = open("  world:add_circle{ radius = 0.5, position = {2, 0} }\n");
  CHECK(plain->camera.pixels_per_metre == doctest::Approx(72.0));
  CHECK(plain->camera.worldToScreen(Vec2(0, 0)).x() == doctest::Approx(area.middle().x()));
  // A ball the whole window would show at x = 7, beside the free area at 72 px/m: the view zooms
  // out about its centre until the ball is between the panels.
  auto wide = open("  world:add_circle{ name = 'far', radius = 0.5, position = {7, 0} }\n");
  CHECK(wide->camera.pixels_per_metre < 72.0);
  CHECK(wide->camera.worldToScreen(Vec2(0, 0)).x() == doctest::Approx(area.middle().x()));
  CHECK(wide->camera.worldToScreen(Vec2(7.5, 0)).x() <= area.upper.x());
  CHECK(wide->camera.worldToScreen(Vec2(7.5, 0)).x() >= area.upper.x() - 0.05 * area.width());
  // A ball outside the scene's view does not count: the scene means it to come into view.
  auto outside = open("  world:add_circle{ radius = 0.5, position = {30, 0} }\n");
  CHECK(outside->camera.pixels_per_metre == doctest::Approx(72.0));
}

TEST_CASE("profile: the session records each step's stage times for the Profile panel") {
  TempDir dir;
  Session s;
  startOn(s, dir.path / "thrown.lua", thrownBall("ball"));
  REQUIRE(s.scene_loaded);
  CHECK(s.profile.steps() == 0);
  frames(s, 10);
  CHECK(s.profile.steps() == 10);
  CHECK(s.profile.stage(kProfileStages.size() - 1).last == doctest::Approx(s.world().stats().total_ms()));
  stepOnce(s);
  CHECK(s.profile.steps() == 11);
  requestLoad(s, s.file, LoadPurpose::Reset);
  REQUIRE(pump(s, [&] { return s.reloads >= 1; }));
  CHECK(s.profile.steps() == 0);  // a new world: its own profile
}
