// world:snapshot() and world:restore(s): the restored world repeats its steps bit for bit, handles
// keep working, bodies made after the snapshot are stale, and misuse is an error in the API's words.
#include <doctest/doctest.h>

#include <string>

#include "rigidlab/lua/scene.h"
#include "scene_test_util.h"

using namespace rigidlab;
using lua_test::errorOf;
using lua_test::load;

TEST_CASE("world:restore repeats the steps after world:snapshot bit for bit, with Lua forces and joints") {
  auto scene = load(R"lua(
    function PopulateWorld(world)
      world:add_box{ static = true, width = 20, height = 1, position = {0, -0.5} }
      for i = 0, 3 do world:add_box{ width = 1, height = 1, position = {0, 0.5 + i} } end
      local ball = world:add_circle{ name = "ball", radius = 0.3, position = {3, 4} }
      world:add_revolute{ a = ball, anchor = {3, 5} }
      world:add_force{ body = ball, evaluate = function(s) return 2 - s.velocity.x, 0 end }
    end
    function Check(world)
      local ball = world:find("ball")
      for i = 1, 30 do world:step() end
      local s = world:snapshot()
      assert(s.step_count == 30 and s.time == world.time and s.bytes > 0)
      for i = 1, 90 do world:step() end
      local x, y, w = ball.position.x, ball.position.y, ball.angular_velocity
      local late = world:add_circle{ radius = 1, position = {-5, 5} }
      world:restore(s)
      assert(world.step_count == 30, "step count " .. world.step_count)
      assert(ball.position.x ~= x, "the ball went back")
      local ok, err = pcall(function() return late.position end)
      assert(not ok and err:find("removed"), tostring(err))
      for i = 1, 90 do world:step() end
      assert(ball.position.x == x and ball.position.y == y and ball.angular_velocity == w,
             string.format("%.17g %.17g against %.17g %.17g", ball.position.x, ball.position.y, x, y))
      assert(#world:joints() == 1 and #world:bodies() == 6)
      assert(tostring(s):find("snapshot at t = 0.5"), tostring(s))
    end)lua");
  CHECK_NOTHROW(scene->runCheck());
}

TEST_CASE("world:restore: errors in the API's words") {
  CHECK(errorOf(R"lua(
    function PopulateWorld(world) end
    function Check(world) world:restore(5) end)lua")
            .find("test.lua:3: restore: snapshot must be a snapshot (from world:snapshot()), got 5") != std::string::npos);
  CHECK(errorOf(R"lua(
    function PopulateWorld(world) end
    function Check(world) world:restore() end)lua")
            .find("restore: snapshot must be a snapshot (from world:snapshot()), got nil") != std::string::npos);
  CHECK(errorOf(R"lua(
    function PopulateWorld(world) end
    function Check(world) local s = world:snapshot(); s.time = 3 end)lua")
            .find("snapshot.time: is read-only") != std::string::npos);
  CHECK(errorOf(R"lua(
    function PopulateWorld(world) end
    function Check(world) local s = world:snapshot(); return s.step_cont end)lua")
            .find("snapshot: has no field 'step_cont' (did you mean 'step_count'?)") != std::string::npos);
  CHECK(errorOf(R"lua(
    function PopulateWorld(world)
      local b = world:add_circle{ radius = 1 }
      world:add_force{ body = b, evaluate = function(s) world:snapshot() return 0, 0 end }
    end)lua", 1)
            .find("snapshot: not allowed while the world is stepping") != std::string::npos);
}

TEST_CASE("Scene::snapshot names the scene it came from") {
  // A snapshot handle cannot leave its scene's Lua state, so restore's "another scene" check is a
  // guard; the program's --load-state compares this label with the scene it loads.
  auto a = load("function PopulateWorld(world) end");
  CHECK(a->snapshot().label() == "scene: test.lua\ndt: 0x1.1111111111111p-6\n");
}

TEST_CASE("Scene::restore from a file's bytes, in a freshly loaded scene, repeats the steps") {
  const std::string source = R"lua(
    scene = { dt = 1 / 60 }
    function PopulateWorld(world)
      world:add_box{ static = true, width = 20, height = 1, position = {0, -0.5} }
      local b = world:add_box{ name = "b", width = 1, height = 1, position = {0, 3}, angular_velocity = 2 }
      world:add_force{ body = b, evaluate = function(s) return -s.position.x, 0 end }
      world:add_spring{ a = b, anchor = {2, 6}, stiffness = 30 }
    end)lua";
  auto first = load(source);
  for (int i = 0; i < 40; ++i) first->step();
  const std::string bytes = serializeSnapshot(first->snapshot());
  for (int i = 0; i < 100; ++i) first->step();
  auto second = load(source);
  second->restore(deserializeSnapshot(bytes));
  for (int i = 0; i < 100; ++i) second->step();
  const BodyId a = *first->world().findBody(std::string_view("b")), b = *second->world().findBody(std::string_view("b"));
  CHECK(first->world().body(a).center == second->world().body(b).center);
  CHECK(first->world().body(a).angle == second->world().body(b).angle);
  CHECK(second->world().stepCount() == 140);
}
