// Events and queries through the Lua API: what a scene that uses none of them pays (nothing), what
// delivering events costs, hooks that fail or edit the world, pre_solve functions, and one clean
// message for every mistake with the new options, fields and functions.
#include <doctest/doctest.h>

#include <chrono>
#include <string>
#include <vector>

#include "rigidlab/lua/scene.h"
#include "scene_test_util.h"

using namespace rigidlab;
using lua::SceneError;
using lua_test::errorOf;
using lua_test::load;

namespace {

// Boxes falling onto a floor: `options` go to every box.
std::string boxes(int n, const std::string& options) {
  return "world:add_box{ width = " + std::to_string(2 * n + 2) + ", height = 1, position = {0, -0.5}, static = true }\n"
         "for i = 1, " + std::to_string(n) + " do world:add_box{ width = 0.5, height = 0.5, position = {2 * i - " +
         std::to_string(n + 1) + ", 0.3}, " + options + " } end\n";
}

}  // namespace

TEST_CASE("events: a scene with no event hook and no flagged shape makes no Lua call and keeps no events") {
  auto scene = load("function PopulateWorld(world)\n" + boxes(3, "") +
                    "  world:add_circle{ radius = 1, position = {0, 3}, static = true, sensor = true }\n"
                    "  before = collectgarbage('count')\n"
                    "end\n"
                    "function Check(world) assert(collectgarbage('count') <= before + 1, 'Lua memory grew') end");
  const long calls = scene->luaCalls();
  for (int i = 0; i < 60; ++i) {
    scene->step();
    CHECK(scene->world().contactEvents().empty());
  }
  CHECK(scene->luaCalls() == calls);
  scene->runCheck();

  // A hook defined, but no shape asks for contact events: still no call.
  auto hooked = load("function PopulateWorld(world)\n" + boxes(3, "") + "end\nfunction OnContactBegin(world, c) end");
  const long before = hooked->luaCalls();
  for (int i = 0; i < 60; ++i) hooked->step();
  CHECK(hooked->luaCalls() == before);
}

TEST_CASE("events: every begin event is one hook call, the cost of delivering 1000 of them") {
  constexpr int kBoxes = 1000;
  auto scene = load("function PopulateWorld(world)\n" + boxes(kBoxes, "contact_events = true") +
                    "end\nbegins = 0\nfunction OnContactBegin(world, c) begins = begins + 1 end\n"
                    "function Check(world) assert(begins == " + std::to_string(kBoxes) + ", begins) end");
  double delivered_ms = 0;
  long calls = 0;
  for (int i = 0; i < 60; ++i) {
    const long before = scene->luaCalls();
    const auto t0 = std::chrono::steady_clock::now();
    scene->step();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (scene->luaCalls() - before > 0) {
      delivered_ms += ms - scene->world().stats().total_ms();  // the step's Lua part only
      calls += scene->luaCalls() - before;
    }
  }
  CHECK(calls == kBoxes);
  MESSAGE("delivering " << calls << " begin events to OnContactBegin: " << delivered_ms << " ms ("
                        << 1000.0 * delivered_ms / static_cast<double>(calls) << " us per event)");
  scene->runCheck();
}

TEST_CASE("events: hooks may edit the world, a body removed by an earlier hook is seen as removed by a later one") {
  auto scene = load(R"lua(
    seen = {}
    function PopulateWorld(world)
      world:add_box{ width = 20, height = 1, position = {0, -0.5}, static = true }
      first = world:add_box{ name = "first", width = 0.5, height = 0.5, position = {-2, 0.3}, contact_events = true }
      second = world:add_box{ name = "second", width = 0.5, height = 0.5, position = {2, 0.3}, contact_events = true }
    end
    function OnContactBegin(world, c)
      seen[#seen + 1] = c.b.removed and "removed" or c.b.name
      if c.b == first then
        world:remove(second)  -- removed before its own begin event is delivered
        world:add_circle{ name = "added in a hook", radius = 0.2, position = {0, 3} }
        first:apply_impulse{0, 1}
        world:step()  -- even a step: the events still being delivered were made before
      end
    end
    function Check(world)
      assert(#seen == 2 and seen[1] == "first" and seen[2] == "removed", table.concat(seen, ","))
      assert(world:find("added in a hook"), "no body was added")
      assert(second.removed)
    end)lua");
  for (int i = 0; i < 30; ++i) scene->step();
  scene->runCheck();
}

TEST_CASE("events: a failing hook or pre_solve is one message at its line, a failed pre_solve undoes the step") {
  CHECK(errorOf("function PopulateWorld(world)\n" + boxes(1, "contact_events = true") +
                    "end\nfunction OnContactBegin(world, c)\n  error('boom')\nend",
                30) == "test.lua:6: OnContactBegin: boom");
  CHECK(errorOf("function PopulateWorld(world)\n" + boxes(1, "hit_speed = 0") +
                    "end\nfunction OnHit(world, c) local x = c.nope + 1 end",
                30)
            .starts_with("test.lua:5: OnHit: attempt to perform arithmetic on a nil value (field 'nope')"));
  CHECK(errorOf("function PopulateWorld(world)\n" + boxes(1, "pre_solve = function(c)\n  error('no') end") + "end", 10) ==
        "test.lua:4: pre_solve: no");
  // Editing the world from inside the step is refused, naming what was tried.
  CHECK(errorOf("function PopulateWorld(world)\n" + boxes(1, "pre_solve = function(c) c.b:apply_impulse{0, 1} end") +
                    "end",
                10) == "test.lua:3: apply_impulse: not allowed while the world is stepping (from inside a force)");
  auto scene = load("function PopulateWorld(world)\n" + boxes(1, "pre_solve = function(c) if fail then error('x') end end") +
                    "end\nfunction OnStep(world) fail = true end");
  bool failed = false;
  for (int i = 0; i < 10 && !failed; ++i) {
    const double t = scene->world().time();
    try {
      scene->step();
    } catch (const SceneError&) {
      failed = true;
      CHECK(scene->world().time() == t);  // the step was undone
    }
  }
  CHECK(failed);
}

TEST_CASE("events: pre_solve is asked only about its shape's contacts, and false lets a body through") {
  auto scene = load(R"lua(
    calls = 0
    function PopulateWorld(world)
      world:add_box{ width = 20, height = 1, position = {0, -0.5}, static = true }
      ghost = world:add_box{ width = 1, height = 1, position = {-3, 0.6},
                             pre_solve = function(c) calls = calls + 1; return false end }
      solid = world:add_box{ width = 1, height = 1, position = {3, 0.6} }
      kept = world:add_box{ width = 1, height = 1, position = {6, 0.6}, pre_solve = function(c) return nil end }
    end
    function Check(world)
      assert(calls > 0, "never asked")
      assert(ghost.position.y < -1, "the ghost did not fall through: " .. ghost.position.y)
      assert(math.abs(solid.position.y - 0.5) < 0.01 and math.abs(kept.position.y - 0.5) < 0.01, "fell")
      assert(type(ghost.shapes[1].pre_solve) == "function" and solid.shapes[1].pre_solve == nil)
      local before = calls
      kept.shapes[1].pre_solve = nil
      ghost.shapes[1].pre_solve = nil
      world:step()
      assert(calls == before and ghost.shapes[1].pre_solve == nil, "asked after pre_solve = nil")
    end)lua");
  for (int i = 0; i < 60; ++i) scene->step();
  scene->runCheck();
}

TEST_CASE("events: OnJointBreak gets the broken joint, shape event fields read back what was given") {
  auto scene = load(R"lua(
    function PopulateWorld(world)
      world:add_box{ width = 20, height = 1, position = {0, -0.5}, static = true }
      local b = world:add_box{ width = 1, height = 1, position = {0, 5} }
      world:add_distance{ a = b, anchor_b = {0, 8}, break_force = 1, name = "rope" }
      s = b.shapes[1]
      p = world:add_box{ width = 4, height = 0.2, position = {0, 2}, static = true, one_way = {0, 2},
                         hit_speed = 2.5 }
    end
    function OnJointBreak(world, joint) broke = joint end
    function Check(world)
      assert(broke and broke.broken and broke.kind == "distance", tostring(broke))
      assert(s.contact_events == false and s.hit_events == false and s.hit_speed == 1 and s.one_way == nil)
      local q = p.shapes[1]
      assert(q.one_way.x == 0 and q.one_way.y == 1, "one_way is normalised")
      assert(q.hit_events == true and q.hit_speed == 2.5, "hit_speed turns hit_events on")
      s.contact_events, s.hit_events, s.hit_speed, s.one_way = true, true, 0, {1, 0}
      assert(s.contact_events and s.hit_events and s.hit_speed == 0 and s.one_way.x == 1)
      s.one_way = nil
      assert(s.one_way == nil)
    end)lua");
  for (int i = 0; i < 5; ++i) scene->step();
  scene->runCheck();
}

TEST_CASE("events and queries: mistakes are one message at the caller's line naming the field and the value") {
  const std::pair<const char*, const char*> cases[] = {
      {"world:add_box{ width = 1, height = 1, hit_speed = -1 }", "add_box: hit_speed must be >= 0, got -1"},
      {"world:add_box{ width = 1, height = 1, contact_event = true }",
       "add_box: unknown option 'contact_event' (did you mean 'contact_events'?)"},
      {"world:add_circle{ radius = 1, one_way = {0, 0} }",
       "add_circle: one_way must be a direction {nx, ny} (the side to stand on), got (0, 0)"},
      {"world:add_circle{ radius = 1, one_way = 'up' }",
       "add_circle: one_way must be a vector {x, y} or vec2(x, y), got \"up\""},
      {"world:add_chain{ points = {{0, 0}, {1, 0}}, pre_solve = true }",
       "add_chain: pre_solve must be a function(contact) that returns false to disable the contact, got true"},
      {"world:add_body{ contact_events = true }",
       "add_body: contact_events is an option of a shape, and add_body makes a body without shapes"},
      {"world:add_body{}:add_shape{ shape = 'circle', radius = 1, hit_events = 1 }",
       "add_shape: hit_events must be true or false, got 1"},
      {"world:add_circle{ radius = 1 }.shapes[1].one_way = {0, 0}",
       "shape.one_way: must be a direction {nx, ny} (the side to stand on), got (0, 0)"},
      {"world:add_circle{ radius = 1 }.shapes[1].pre_solve = 5",
       "shape.pre_solve: must be a function(contact) that returns false to disable the contact, or nil, got 5"},
      {"local x = world:add_circle{ radius = 1 }.shapes[1].hit_sped", "shape: has no field 'hit_sped' (did you mean 'hit_speed'?)"},
      {"world:add_circle{ radius = 1 }.contacts()", "contacts: call it as body:contacts(), with a colon; got nil as the body"},
      {"world:ray_cast{ from = {0, 0} }", "ray_cast: to is required"},
      {"world:ray_cast{ from = {0, 0}, to = {1, 0}, sensor = true }",
       "ray_cast: unknown option 'sensor' (did you mean 'sensors'?)"},
      {"world:ray_cast_all{ from = {0, 0}, to = {1, 0/0} }", "ray_cast_all: to must be finite, got (1, nan)"},
      {"world:ray_cast{ from = {0, 0}, to = {1, 0}, mask = 0.5 }",
       "ray_cast: mask must be an integer set of bits (e.g. 1 << 3, 0x8 or -1 for all 64), got 0.5"},
      {"world:query_box{ lower = {1, 1}, upper = {0, 2} }",
       "query_box: upper must be above and right of lower (upper >= lower in x and y), got lower (1, 1) and upper (0, 2)"},
      {"world:query_point{ point = 3 }", "query_point: point must be a vector {x, y} or vec2(x, y), got 3"},
      {"world:overlap{ shape = 'circle' }",
       "overlap: shape must be a table like body:add_shape's, e.g. {shape = \"circle\", radius = 0.5}, got \"circle\""},
      {"world:overlap{ shape = { shape = 'circle', radius = -1 } }", "overlap: shape: radius must be > 0, got -1"},
      {"world:overlap{ shape = { shape = 'circle', width = 1 } }",
       "overlap: shape: width is not an option of a circle shape (it takes radius)"},
      {"world:overlap{ shape = { shape = 'segment', a = {0, 0}, b = {1, 0} } }",
       "overlap: shape: shape \"segment\" cannot be used here: queries take a circle, box, polygon or capsule"},
      {"world:shape_cast{ shape = { shape = 'box', width = 1, height = 1 }, from = {0, 0} }", "shape_cast: to is required"},
      {"world:explode{ position = {0, 0}, radius = 0 }", "explode: radius must be > 0, got 0"},
      {"world:explode{ position = {0, 0}, sensors = true }", "explode: unknown option 'sensors'"},
      {"world.ray_cast{ from = {0, 0}, to = {1, 0} }", "ray_cast: call it as world:ray_cast(...), with a colon"},
      {"world:add_force{ body = world:add_circle{ radius = 1 }, evaluate = function(s) world:ray_cast{ from = {0, 0}, to = {1, 0} } return 0, 0 end }",
       "ray_cast: not allowed while the world is stepping (from inside a force)"},
  };
  for (const auto& [line, message] : cases) {
    const std::string source = std::string("function PopulateWorld(world)\n  ") + line + "\nend";
    CAPTURE(source);
    const std::string m = errorOf(source, 1);
    CAPTURE(m);
    CHECK(m.find('\n') == std::string::npos);
    CHECK(m.starts_with("test.lua:2: " + std::string(message)));
  }
}
