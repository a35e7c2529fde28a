// The sandbox's mod hooks through the real bindings: OnMouse's event table and its answer,
// OnDraw(draw, world) with filled shapes and draw.screen, scene.keys, scene.controls with
// world.controls and OnControl, and the messages for their mistakes.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "rigidlab/lua/scene.h"

using namespace rigidlab;
using rigidlab::lua::MouseEvent;
using rigidlab::lua::Scene;
using rigidlab::lua::SceneError;

namespace {

std::unique_ptr<Scene> load(const std::string& source, std::vector<std::string>* log = nullptr,
                            lua::SceneOptions options = {}) {
  options.log = [log](const std::string& line) {
    if (log) log->push_back(line);
  };
  return Scene::loadString(source, "mod.lua", options);
}

std::string errorOf(const std::string& source) {
  try {
    load(source);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

MouseEvent press(MouseEvent::Button button, Vec2 position, Vec2 screen) {
  MouseEvent e;
  e.kind = MouseEvent::Kind::Press;
  e.button = button;
  e.position = position;
  e.screen = screen;
  return e;
}

// Prints every field of the event OnMouse gets; consumes left presses only.
constexpr const char* kPrintingScene = R"lua(
function PopulateWorld(world) end
local function show(v) if v == nil then return "nil" end return tostring(v) end
function OnMouse(world, e)
  print(string.format("%s %s %.2f,%.2f %.0f,%.0f %s %s %s %s", e.kind, show(e.button), e.position.x,
                      e.position.y, e.screen.x, e.screen.y, show(e.shift), show(e.ctrl), show(e.alt), show(e.wheel)))
  if e.kind == "press" and e.button == "left" then
    world:add_circle{radius = 0.5, position = e.position}
    return true
  end
  if e.kind == "release" then return nil end
  return false
end)lua";

}  // namespace

TEST_CASE("mod hooks: OnMouse gets kind, button, position, screen, modifiers and wheel, true consumes") {
  std::vector<std::string> log;
  auto scene = load(kPrintingScene, &log);
  REQUIRE(scene->hasOnMouse());
  CHECK(scene->onMouse(press(MouseEvent::Button::Left, Vec2(1.5, -2), Vec2(748, 504))));
  CHECK_FALSE(scene->onMouse(press(MouseEvent::Button::Right, Vec2(0, 0), Vec2(640, 360))));
  MouseEvent middle = press(MouseEvent::Button::Middle, Vec2(0, 0), Vec2(640, 360));
  middle.kind = MouseEvent::Kind::Release;
  middle.shift = middle.ctrl = middle.alt = true;
  CHECK_FALSE(scene->onMouse(middle));  // nil: not consumed
  MouseEvent move;
  move.position = Vec2(0.25, 0.75);
  move.screen = Vec2(658, 306);
  move.ctrl = true;
  CHECK_FALSE(scene->onMouse(move));
  MouseEvent wheel = move;
  wheel.kind = MouseEvent::Kind::Wheel;
  wheel.wheel = -2;
  CHECK_FALSE(scene->onMouse(wheel));
  REQUIRE(log.size() == 5);
  CHECK(log[0] == "press left 1.50,-2.00 748,504 false false false nil");
  CHECK(log[1] == "press right 0.00,0.00 640,360 false false false nil");
  CHECK(log[2] == "release middle 0.00,0.00 640,360 true true true nil");
  CHECK(log[3] == "move nil 0.25,0.75 658,306 false true false nil");
  CHECK(log[4] == "wheel nil 0.25,0.75 658,306 false true false -2.0");
  // The world was edited from the hook: a body where the left press was.
  REQUIRE(scene->world().bodyCount() == 1);
  CHECK(scene->world().body(scene->world().bodyIds()[0]).xf.p == Vec2(1.5, -2));
}

TEST_CASE("mod hooks: OnMouse must answer true, false or nothing, a scene without it consumes nothing") {
  const auto mouseError = [](const std::string& hook) {
    try {
      load("function PopulateWorld(world) end\n" + hook)->onMouse(MouseEvent{});
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  CHECK(mouseError("function OnMouse(world, e) return 1 end") ==
        "mod.lua: OnMouse: must return true (the event is consumed), false or nothing, got 1");
  CHECK(mouseError("function OnMouse(world, e)\n  error('boom')\nend") == "mod.lua:3: OnMouse: boom");
  CHECK(mouseError("OnMouse = 5") == "mod.lua: OnMouse must be a function, got 5");
  auto plain = load("function PopulateWorld(world) end");
  CHECK_FALSE(plain->hasOnMouse());
  CHECK_FALSE(plain->onMouse(press(MouseEvent::Button::Left, Vec2(0, 0), Vec2(0, 0))));
}

namespace {

// Records what a scene draws; screen pixels map to world (px / 10, −py / 10).
struct Recorder : lua::OverlayDraw {
  std::vector<std::string> calls;
  static std::string at(const Vec2& p) { return std::to_string(p.x()).substr(0, 5) + "," + std::to_string(p.y()).substr(0, 5); }
  void line(const Vec2& a, const Vec2& b, const Color&) override { calls.push_back("line " + at(a) + " " + at(b)); }
  void circle(const Vec2& c, double r, const Color&) override { calls.push_back("circle " + at(c) + " r" + std::to_string(r).substr(0, 4)); }
  void text(const Vec2& p, const std::string& t, const Color&) override { calls.push_back("text " + at(p) + " " + t); }
  void polygon(std::span<const Vec2> points, const Color&, const std::optional<Color>& fill) override {
    calls.push_back("polygon " + std::to_string(points.size()) + " " + at(points[1]) + (fill ? " filled" : ""));
  }
  void capsule(const Vec2& a, const Vec2& b, double r, const Color&, const std::optional<Color>& fill) override {
    calls.push_back("capsule " + at(a) + " " + at(b) + " r" + std::to_string(r).substr(0, 4) + (fill ? " filled" : ""));
  }
  void disc(const Vec2& c, double r, const Color&, const Color& fill) override {
    calls.push_back("disc " + at(c) + " r" + std::to_string(r).substr(0, 4) + " fill " + std::to_string(fill.g).substr(0, 3));
  }
  Vec2 screenToWorld(const Vec2& px) const override { return Vec2(px.x() / 10, -px.y() / 10); }
  double metresPerPixel() const override { return 0.1; }
};

}  // namespace

TEST_CASE("mod hooks: OnDraw gets the world, polygons, capsules, fills and draw.screen in pixels") {
  auto scene = load(R"lua(
scene = {title = "hud"}
function PopulateWorld(world) world:add_circle{radius = 1} end
function OnDraw(draw, world)
  draw:text({0, 0}, world.title .. " " .. #world:bodies())
  draw:circle({1, 2}, 0.5, nil, {0, 0.5, 0})
  draw:polygon({{0, 0}, {2, 0}, {1, 1}}, {1, 1, 1}, {1, 0, 0, 0.5})
  draw:capsule({0, 0}, {1, 0}, 0.25)
  draw.screen:line({10, 20}, {30, 40})
  draw.screen:circle({100, 50}, 20)
  draw.screen:polygon({{0, 0}, {50, 0}, {50, 50}, {0, 50}}, nil, {0, 0, 0})
  draw.screen:capsule({0, 10}, {20, 10}, 5, {1, 1, 1}, {1, 1, 1})
  draw.screen:text({5, 5}, "score")
end)lua");
  Recorder r;
  const Scene::DrawReport report = scene->onDraw(r);
  const std::vector<std::string> expected = {
      "text 0.000,0.000 hud 1",
      "disc 1.000,2.000 r0.50 fill 0.5",
      "polygon 3 2.000,0.000 filled",
      "capsule 0.000,0.000 1.000,0.000 r0.25",
      "line 1.000,-2.00 3.000,-4.00",
      "circle 10.00,-5.00 r2.00",
      "polygon 4 5.000,-0.00 filled",
      "capsule 0.000,-1.00 2.000,-1.00 r0.50 filled",
      "text 0.500,-0.50 score",
  };
  CHECK(r.calls == expected);
  CHECK(report.shapes == 4);
  CHECK(report.circles == 2);
  CHECK_FALSE(report.truncated);
}

TEST_CASE("mod hooks: draw mistakes name the function, the argument and the bad value") {
  const auto drawError = [](const std::string& body) {
    auto scene = load("function PopulateWorld(world) end\nfunction OnDraw(draw, world)\n  " + body + "\nend");
    Recorder r;
    try {
      scene->onDraw(r);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  CHECK(drawError("draw:polygon({{0, 0}, {1, 0}})") == "mod.lua:3: polygon: points needs at least 3 points, got 2");
  CHECK(drawError("draw:polygon({{0, 0}, {1, 0}, {1, 1}}, nil, {2, 0, 0})") ==
        "mod.lua:3: polygon: fill must be {r, g, b [, a]} with values in 0..1, got a table");
  CHECK(drawError("draw.screen:capsule({0, 0}, {1, 0}, -1)") == "mod.lua:3: capsule: radius must be a number > 0, got -1");
  CHECK(drawError("draw:circle({0, 0}, 1, {1, 1, 1}, 'red')") ==
        "mod.lua:3: circle: fill must be {r, g, b [, a]} with values in 0..1, got \"red\"");
  CHECK(drawError("draw:rectangle({0, 0})") == "mod.lua:3: draw: has no function 'rectangle'");
  CHECK(drawError("draw:polygn({0, 0})") == "mod.lua:3: draw: has no function 'polygn' (did you mean 'polygon'?)");
}

TEST_CASE("mod hooks: scene.keys lists the keys a scene takes from the sandbox") {
  auto scene = load("scene = {keys = {'space', 'r', 'f1'}}\nfunction PopulateWorld(world) end");
  CHECK(scene->settings().keys == std::vector<std::string>{"space", "r", "f1"});
  CHECK(load("function PopulateWorld(world) end")->settings().keys.empty());
  CHECK(errorOf("\nscene = {\n  keys = {'space', 'Space'},\n}\nfunction PopulateWorld(world) end") ==
        "mod.lua:2: scene: keys[2] must be a key name in lower case as OnKey receives it (\"space\", \"a\", \"f1\"), got \"Space\"");
  CHECK(errorOf("scene = {keys = 'space'}\nfunction PopulateWorld(world) end") ==
        "mod.lua:1: scene: keys must be a list, e.g. {\"space\", \"a\"}, got \"space\"");
  CHECK(errorOf("scene = {controsl = {}}\nfunction PopulateWorld(world) end") ==
        "mod.lua:1: scene: unknown option 'controsl' (did you mean 'controls'?)");
}

namespace {

constexpr const char* kControlsScene = R"lua(
scene = {
  controls = {
    {name = "wind", min = 0, max = 20, value = 5},
    {name = "count", min = 1, max = 10},
    {name = "reset", kind = "button"},
  },
}
pressed = {}
function PopulateWorld(world)
  for i = 1, world.controls.count do world:add_circle{radius = 0.1, position = {i, 0}} end
  print("wind " .. world.controls.wind)
end
function OnControl(world, name)
  print("control " .. name .. " wind " .. world.controls.wind)
  if name == "reset" then world.controls.wind = 0 end
end)lua";

}  // namespace

TEST_CASE("mod hooks: scene.controls: sliders read and set through world.controls, buttons call OnControl") {
  std::vector<std::string> log;
  auto scene = load(kControlsScene, &log);
  const auto& controls = scene->settings().controls;
  REQUIRE(controls.size() == 3);
  CHECK(controls[0].name == "wind");
  CHECK(controls[0].min == 0);
  CHECK(controls[0].max == 20);
  CHECK(controls[1].value == 1);  // default: min
  CHECK(controls[2].kind == lua::SceneSettings::Control::Kind::Button);
  CHECK(scene->world().bodyCount() == 1);
  REQUIRE(log.size() == 1);
  CHECK(log[0] == "wind 5.0");
  scene->setControlValue(0, 25);  // clamped into the range
  CHECK(scene->controlValue(0) == 20);
  scene->setControlValue(2, 3);  // a button has no value
  CHECK(scene->controlValue(2) == 0);
  scene->onControl("wind");
  scene->onControl("reset");
  CHECK(scene->controlValue(0) == 0);  // set from Lua
  CHECK(log.back() == "control reset wind 20.0");
  CHECK(scene->controlValues() == std::map<std::string, double>{{"count", 1}, {"wind", 0}});

  // Kept across a reload: the sandbox passes the running values.
  lua::SceneOptions options;
  options.control_values = {{"wind", 7}, {"count", 30}, {"gone", 1}};
  auto reloaded = load(kControlsScene, &log, options);
  CHECK(reloaded->controlValue(0) == 7);
  CHECK(reloaded->controlValue(1) == 10);  // clamped into the new range
  CHECK(reloaded->world().bodyCount() == 10);
}

TEST_CASE("mod hooks: world.controls and scene.controls mistakes name the field and the bad value") {
  const auto runError = [](const std::string& body) {
    try {
      load(std::string(kControlsScene) + "\nfunction Check(world)\n  " + body + "\nend")->runCheck();
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  CHECK(runError("world.controls.wind = 21") == "mod.lua:19: world.controls.wind: must be between 0 and 20, got 21");
  CHECK(runError("world.controls.wind = 'x'") == "mod.lua:19: world.controls.wind: must be a number, got \"x\"");
  CHECK(runError("local x = world.controls.reset") ==
        "mod.lua:19: world.controls.reset: is a button, it has no value (OnControl(world, name) is called when it is pressed)");
  CHECK(runError("local x = world.controls.wnd") == "mod.lua:19: world.controls: has no control 'wnd'");
  CHECK(runError("local x = world.controls.cuont") == "mod.lua:19: world.controls: has no control 'cuont' (did you mean 'count'?)");
  CHECK(runError("world.controls = {}") == "mod.lua:19: world.controls: is read-only");

  // scene.controls mistakes: reported at the scene table's line.
  const std::pair<const char*, const char*> cases[] = {
      {"{{name = 'wind', min = 5, max = 5}}", "scene.controls[1]: max must be greater than min (5), got 5"},
      {"{{name = 'a', kind = 'button'}, {name = 'wind', min = 0, max = 1, value = 2}}",
       "scene.controls[2]: value must be between min and max (0 and 1), got 2"},
      {"{{name = 'go', kind = 'knob'}}", "scene.controls[1]: kind must be \"slider\" or \"button\", got \"knob\""},
      {"{{name = 'go', kind = 'button', max = 3}}", "scene.controls[1]: max is for sliders; a button has none, got 3"},
      {"{{name = 'wind speed', min = 0, max = 1}}",
       "scene.controls[1]: name must be a name of letters, digits and underscores (world.controls.<name>), got \"wind speed\""},
      {"{{name = 'a', kind = 'button'}, {name = 'a', kind = 'button'}}",
       "scene.controls[2]: name 'a' is used by an earlier control"},
      {"{{name = 'a', min = 0, max = 1, vaule = 1}}", "scene.controls[1]: unknown option 'vaule' (did you mean 'value'?)"},
      {"{{name = 'wind', max = 1}}", "scene.controls[1]: min is required"},
      {"'wind'", "scene: controls must be a list, e.g. {{name = \"wind\", min = 0, max = 20, value = 5}}, got \"wind\""},
  };
  for (const auto& [controls, message] : cases) {
    CAPTURE(controls);
    CHECK(errorOf("\nscene = {\n  controls = " + std::string(controls) + ",\n}\nfunction PopulateWorld(world) end") ==
          "mod.lua:2: " + std::string(message));
  }
}
