// The sandbox's side of the mod hooks, without a window: SDL mouse events as OnMouse's events
// (through the camera), consuming them, keys a scene takes (scene.keys), the Controls' values kept
// across a hot reload, framing in the area the panels leave free, and picking through the world's
// queries.
#include <doctest/doctest.h>

#include "mouse_event.h"
#include "panel_layout.h"
#include "picking.h"
#include "session_helpers.h"

using namespace rigidlab;
using namespace rigidlab::sandbox;
using namespace rigidlab::sandbox::testing;
using lua::MouseEvent;

namespace {

Camera camera1280() {
  Camera c;
  c.resize(1280, 720);
  c.center = Vec2(1, 2);
  c.setHeightMetres(10.0);  // 72 px per metre: world (x, y) → pixel (640 + 72 (x − 1), 360 − 72 (y − 2))
  return c;
}

SDL_Event wheel(float notches, bool flipped = false) {
  SDL_Event e{};
  e.type = SDL_MOUSEWHEEL;
  e.wheel.preciseY = notches;
  e.wheel.y = static_cast<Sint32>(notches);
  e.wheel.direction = flipped ? SDL_MOUSEWHEEL_FLIPPED : SDL_MOUSEWHEEL_NORMAL;
  return e;
}

}  // namespace

TEST_CASE("mod input: SDL mouse events become OnMouse events with world coordinates through the camera") {
  const Camera c = camera1280();
  const Vec2 cursor(0, 0);
  const auto down = sceneMouseEvent(mouse(SDL_MOUSEBUTTONDOWN, Vec2(784, 216)), c, cursor, KMOD_NONE);
  REQUIRE(down);
  CHECK(down->kind == MouseEvent::Kind::Press);
  CHECK(down->button == MouseEvent::Button::Left);
  CHECK(down->screen == Vec2(784, 216));
  CHECK(down->position.x() == doctest::Approx(3.0));  // 1 + 144 / 72
  CHECK(down->position.y() == doctest::Approx(4.0));  // 2 + 144 / 72
  CHECK_FALSE(down->shift);

  const auto up = sceneMouseEvent(mouse(SDL_MOUSEBUTTONUP, Vec2(640, 432), SDL_BUTTON_RIGHT), c, cursor, KMOD_LSHIFT);
  REQUIRE(up);
  CHECK(up->kind == MouseEvent::Kind::Release);
  CHECK(up->button == MouseEvent::Button::Right);
  CHECK(up->position.y() == doctest::Approx(1.0));
  CHECK(up->shift);
  CHECK_FALSE(up->ctrl);

  const auto middle = sceneMouseEvent(mouse(SDL_MOUSEBUTTONDOWN, Vec2(0, 0), SDL_BUTTON_MIDDLE), c, cursor,
                                      static_cast<SDL_Keymod>(KMOD_RCTRL | KMOD_LALT));
  REQUIRE(middle);
  CHECK(middle->button == MouseEvent::Button::Middle);
  CHECK(middle->ctrl);
  CHECK(middle->alt);
  CHECK_FALSE(sceneMouseEvent(mouse(SDL_MOUSEBUTTONDOWN, Vec2(0, 0), SDL_BUTTON_X1), c, cursor, KMOD_NONE));

  const auto move = sceneMouseEvent(mouse(SDL_MOUSEMOTION, Vec2(640, 360)), c, cursor, KMOD_NONE);
  REQUIRE(move);
  CHECK(move->kind == MouseEvent::Kind::Move);
  CHECK(move->button == MouseEvent::Button::None);
  CHECK(move->position == Vec2(1, 2));  // the middle of the window is the camera's centre

  // A wheel event carries no position: the cursor's is used. Notches > 0 away from the user.
  const auto turn = sceneMouseEvent(wheel(2), c, Vec2(712, 360), KMOD_NONE);
  REQUIRE(turn);
  CHECK(turn->kind == MouseEvent::Kind::Wheel);
  CHECK(turn->wheel == 2);
  CHECK(turn->position.x() == doctest::Approx(2.0));
  CHECK(sceneMouseEvent(wheel(1, true), c, cursor, KMOD_NONE)->wheel == -1);
  CHECK_FALSE(sceneMouseEvent(key(SDLK_a), c, cursor, KMOD_NONE));
}

namespace {

constexpr const char* kSpawner = R"(
scene = {title = "spawner", gravity = {0, 0}, camera = {center = {0, 0}, height = 10}, keys = {"space", "n"}}
keys = {}
function PopulateWorld(world) end
function OnMouse(world, e)
  if e.kind == "press" and e.button == "left" and not e.shift then
    world:add_circle{radius = 0.25, position = e.position, name = "spawned"}
    return true
  end
end
function OnKey(world, key) keys[#keys + 1] = key; world:add_box{width = 0.1, height = 0.1, position = {0, #keys}} end
)";

}  // namespace

TEST_CASE("mod input: a consumed click is the scene's, not the tool's, others still reach the tools") {
  TempDir dir;
  Session s;
  startOn(s, dir.path / "spawner.lua", kSpawner);
  REQUIRE(s.scene_loaded);
  selectTool(s, Tool::Circle);  // the circle tool would add a circle on the release
  click(s, Vec2(2, 1));
  REQUIRE(s.world().bodyCount() == 1);
  const Body& spawned = s.world().body(*s.world().findBody("spawned"));
  CHECK(spawned.xf.p.x() == doctest::Approx(2.0));
  CHECK(spawned.xf.p.y() == doctest::Approx(1.0));
  CHECK(s.tools.gesture == ToolState::Gesture::None);
  // Shift + click: the scene returns nothing, the circle tool adds its circle.
  const Vec2 px = s.camera.worldToScreen(Vec2(-2, -1));
  SDL_SetModState(KMOD_LSHIFT);
  handleEvent(s, mouse(SDL_MOUSEBUTTONDOWN, px), {});
  handleEvent(s, mouse(SDL_MOUSEBUTTONUP, px), {});
  SDL_SetModState(KMOD_NONE);
  CHECK(s.world().bodyCount() == 2);
  // Over a panel (ImGui wants the mouse) the scene gets nothing.
  handleEvent(s, mouse(SDL_MOUSEBUTTONDOWN, s.camera.worldToScreen(Vec2(0, 3))), {true, false});
  CHECK(s.world().bodyCount() == 2);
}

TEST_CASE("mod input: scene.keys takes keys from the sandbox's bindings, the others keep theirs") {
  TempDir dir;
  Session s;
  startOn(s, dir.path / "spawner.lua", kSpawner);
  REQUIRE(s.scene_loaded);
  CHECK_FALSE(s.paused);
  handleEvent(s, key(SDLK_SPACE), {});  // the scene's now, not pause
  handleEvent(s, key(SDLK_n), {});      // not a single step either
  CHECK_FALSE(s.paused);
  CHECK(s.world().stepCount() == 0);
  CHECK(s.world().bodyCount() == 2);
  handleEvent(s, key(SDLK_SPACE, KMOD_LCTRL), {});  // with Ctrl: neither the scene's nor a binding
  CHECK(s.world().bodyCount() == 2);
  handleEvent(s, key(SDLK_TAB), {});  // not taken: the sandbox's (hide the panels)
  CHECK_FALSE(s.show_panels);
  CHECK(s.world().bodyCount() == 2);
}

TEST_CASE("mod input: the Controls' slider values are kept across a hot reload and a reset") {
  TempDir dir;
  const fs::path file = dir.path / "controls.lua";
  const std::string source = R"(
scene = {gravity = {0, 0}, controls = {{name = "count", min = 1, max = 5, value = 1}, {name = "go", kind = "button"}}}
function PopulateWorld(world)
  for i = 1, world.controls.count do world:add_circle{radius = 0.1, position = {i, 0}} end
end
)";
  Session s;
  startOn(s, file, source);
  REQUIRE(s.scene_loaded);
  CHECK(s.world().bodyCount() == 1);
  s.scene->setControlValue(0, 3);
  write(file, source + "-- edited\n");
  REQUIRE(pump(s, [&] { return s.reloads >= 1; }));
  CHECK(s.scene->controlValue(0) == 3);
  CHECK(s.world().bodyCount() == 3);  // PopulateWorld saw the kept value
  requestLoad(s, file, LoadPurpose::Reset);
  REQUIRE(pump(s, [&] { return s.reloads >= 2; }));
  CHECK(s.scene->controlValue(0) == 3);
  requestLoad(s, file, LoadPurpose::Open);  // another scene (or the same, opened again): its defaults
  REQUIRE(pump(s, [&] { return !s.loader.busy() && s.scene->controlValue(0) == 1; }));
}

TEST_CASE("mod input: the initial view and Fit frame the scene in the area the panels leave free") {
  const ScreenRect area = freeViewArea(1280, 720, true);
  CHECK(area.lower == Vec2(2 * kPanelMargin + kLeftPanelWidth, 0));
  CHECK(area.upper == Vec2(1280 - 2 * kPanelMargin - kRightPanelWidth, 720));
  const ScreenRect hidden = freeViewArea(1280, 720, false);
  CHECK(hidden.lower == Vec2(0, 0));
  CHECK(hidden.upper == Vec2(1280, 720));
  CHECK(freeViewArea(700, 500, true).upper == Vec2(700, 500));  // too narrow between the panels: all of it

  // A wide scene: fitted into the free area, no corner of it behind a panel.
  Camera c;
  c.resize(1280, 720);
  const Aabb box{Vec2(-10, 0), Vec2(10, 4)};
  c.fitIn(box, area, 0.9);
  const Vec2 lo = c.worldToScreen(box.lower), hi = c.worldToScreen(box.upper);
  CHECK(lo.x() == doctest::Approx(area.lower.x() + 0.05 * area.width()));
  CHECK(hi.x() == doctest::Approx(area.upper.x() - 0.05 * area.width()));
  CHECK(c.worldToScreen(Vec2(0, 2)).x() == doctest::Approx(area.middle().x()));
  CHECK(c.worldToScreen(Vec2(0, 2)).y() == doctest::Approx(360));
  c.placeAt(Vec2(5, 5), Vec2(100, 50));
  CHECK(c.worldToScreen(Vec2(5, 5)).x() == doctest::Approx(100));
  CHECK(c.worldToScreen(Vec2(5, 5)).y() == doctest::Approx(50));

  // Through the session: a scene without a camera opens framed there; F frames it again, and with
  // the panels hidden (Tab) uses the whole window.
  TempDir dir;
  Session s;
  startOn(s, dir.path / "wide.lua",
          "function PopulateWorld(world)\n  world:add_box{static = true, width = 30, height = 1}\n"
          "  world:add_circle{radius = 1, position = {-14, 3}}\nend\n");
  REQUIRE(s.scene_loaded);
  const Aabb all = *worldBounds(s.world());
  const auto inside = [&](const ScreenRect& r) {
    const Vec2 a = s.camera.worldToScreen(all.lower), b = s.camera.worldToScreen(all.upper);
    return a.x() >= r.lower.x() - 1e-9 && b.x() <= r.upper.x() + 1e-9 && b.y() >= r.lower.y() && a.y() <= r.upper.y();
  };
  CHECK(inside(area));
  s.camera.pan(Vec2(-400, 0));
  CHECK_FALSE(inside(area));
  handleEvent(s, key(SDLK_f), {});
  CHECK(inside(area));
  handleEvent(s, key(SDLK_TAB), {});
  handleEvent(s, key(SDLK_f), {});
  CHECK(s.camera.worldToScreen(0.5 * (all.lower + all.upper)).x() == doctest::Approx(640));
}

TEST_CASE("mod input: picking goes through the world's queries: topmost body, segments within the tolerance") {
  World w;
  BodyDef def;
  def.shape = makeBox(2, 2);
  const BodyId below = w.createBody(def);
  def.shape = makeCircle(0.5);
  def.position = Vec2(0.5, 0);
  const BodyId above = w.createBody(def);
  def.shape = makeSegment(Vec2(-5, 0), Vec2(5, 0));
  def.position = Vec2(0, -3);
  def.type = BodyType::Static;
  const BodyId ground = w.createBody(def);
  CHECK(pickBody(w, Vec2(0.5, 0), 0.1) == above);           // both contain it: the later one
  CHECK(pickBody(w, Vec2(0.5, 0), 0.1, above) == below);    // passed over
  CHECK(pickBody(w, Vec2(-0.8, 0.8), 0.1) == below);
  CHECK(pickBody(w, Vec2(2, -2.95), 0.1) == ground);        // 5 cm from the segment
  CHECK_FALSE(pickBody(w, Vec2(2, -2.8), 0.1));             // 20 cm: too far
  CHECK_FALSE(pickBody(w, Vec2(3, 3), 0.1));
}

TEST_CASE("mod input: a failing OnMouse pauses with its error, and gets no more events until resumed") {
  TempDir dir;
  Session s;
  startOn(s, dir.path / "failing.lua", R"(
scene = {gravity = {0, 0}, camera = {center = {0, 0}, height = 10}}
function PopulateWorld(world) end
function OnMouse(world, e)
  if e.kind ~= "press" then return false end
  world:add_circle{radius = 0.1, position = e.position}
  error("broken tool")
end
)");
  REQUIRE(s.scene_loaded);
  click(s, Vec2(1, 1));
  CHECK(s.paused);
  CHECK(s.run_error.find("failing.lua:7: OnMouse: broken tool") != std::string::npos);
  CHECK(s.world().bodyCount() == 1);
  click(s, Vec2(2, 1));  // not offered: the select tool's (nothing there)
  CHECK(s.world().bodyCount() == 1);
  setPaused(s, false);
  click(s, Vec2(3, 1));
  CHECK(s.world().bodyCount() == 2);
}
