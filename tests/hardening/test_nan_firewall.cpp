// The NaN firewall seen from scenes (docs/design/reliability.md R1, R2; engine/core/src/nan_guard.cpp): a body
// whose state becomes non-finite is frozen and reported with body, step and force, and never
// poisons the bodies around it. Non-finite values from Lua are stopped earlier, at the boundary.
#include <doctest/doctest.h>

#include <cmath>

#include "util.h"

using namespace hardening;
using namespace rigidlab;

namespace {

bool finite(const Body& b) {
  return isFinite(b.center) && std::isfinite(b.angle) && isFinite(b.velocity) && std::isfinite(b.angular_velocity);
}

// Steps the scene, checking after every step that every body is finite.
void stepFinite(Scene& scene, int steps) {
  for (int i = 0; i < steps; ++i) {
    scene.step();
    for (BodyId id : scene.world().bodyIds()) {
      const Body& b = scene.world().body(id);
      CAPTURE(b.uid);
      REQUIRE(finite(b));
    }
  }
}

const Body& named(const Scene& s, const char* name) { return s.world().body(*s.world().findBody(std::string_view(name))); }

}  // namespace

TEST_CASE("NaN firewall: an extreme spring freezes its body, names body, step and force, the box under it stays finite") {
  auto scene = load(R"lua(
    scene = { dt = 1/60 }
    function PopulateWorld(world)
      world:add_box{ name = "ground", width = 20, height = 1, position = {0, -0.5}, static = true }
      local base = world:add_box{ name = "base", width = 2, height = 1, position = {0, 0.5} }
      local wild = world:add_box{ name = "wild", width = 1, height = 1, position = {0, 1.5} }
      world:add_spring{ a = wild, anchor = {0, 100}, stiffness = 1e306, rest_length = 0 }
      world:add_circle{ name = "ball", radius = 0.5, position = {5, 0.5} }
    end)lua");
  stepFinite(*scene, 120);
  const auto& incidents = scene->world().incidents();
  REQUIRE(incidents.size() == 1);
  const Incident& i = incidents.front();
  MESSAGE(i.message());
  CHECK(i.name == "wild");
  CHECK(i.uid == named(*scene, "wild").uid);
  CHECK(i.step == 1);
  CHECK(contains(i.cause, "spring"));
  CHECK(named(*scene, "wild").frozen);
  CHECK(named(*scene, "wild").isStatic());
  // The others simulate on: the base rests on the ground, the ball was never disturbed.
  CHECK_FALSE(named(*scene, "base").frozen);
  CHECK(std::abs(named(*scene, "base").center.y() - 0.5) < 0.05);
  CHECK(named(*scene, "ball").center.x() == doctest::Approx(5.0));
}

TEST_CASE("NaN firewall: a Lua force with a huge finite output blows up its body, which is frozen with the Lua force named") {
  auto scene = load(R"lua(
    function PopulateWorld(world)
      world:add_box{ name = "ground", width = 20, height = 1, position = {0, -0.5}, static = true }
      local rocket = world:add_circle{ name = "rocket", radius = 0.5, position = {0, 0.5}, mass = 1e-3 }
      world:add_force{ body = rocket, evaluate = function(s) return 1e308, 1e308, 1e308 end }
      for i = 1, 3 do world:add_circle{ name = "n" .. i, radius = 0.5, position = {i * 1.01, 0.5} } end
    end)lua");
  stepFinite(*scene, 60);
  const auto& incidents = scene->world().incidents();
  REQUIRE(incidents.size() >= 1);
  MESSAGE(incidents.front().message());
  CHECK(incidents.front().name == "rocket");
  CHECK(contains(incidents.front().cause, "lua force"));
  for (const char* n : {"n1", "n2", "n3"}) CHECK_FALSE(named(*scene, n).frozen);
}

TEST_CASE("NaN firewall: a velocity set huge from Lua overflows the position later, frozen, neighbours fine") {
  auto scene = load(R"lua(
    scene = { gravity = {0, 0} }
    function PopulateWorld(world)
      world:add_circle{ name = "fast", radius = 0.5, position = {0, 0} }
      world:add_circle{ name = "calm", radius = 0.5, position = {0, 3}, velocity = {1, 0} }
    end
    function OnStep(world, dt)
      if world.step_count == 2 then world:find("fast").velocity = {1.7e308, 1.7e308} end
    end)lua");
  stepFinite(*scene, 200);
  REQUIRE(scene->world().incidents().size() == 1);
  MESSAGE(scene->world().incidents().front().message());
  CHECK(scene->world().incidents().front().name == "fast");
  CHECK(named(*scene, "calm").center.x() == doctest::Approx(200.0 / 60.0));
}

TEST_CASE("NaN firewall: non-finite numbers from Lua are refused at the boundary, before the core") {
  const char* cases[][2] = {
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_force{ body = b, evaluate = function(s) return 1e308 * 10, 0 end }\nend",
       "test.lua:3: evaluate: returned a non-finite fx: inf (body id 1, t = 0 s)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_force{ body = b, evaluate = function(s) return 0, 0, 0/0 end }\nend",
       "test.lua:3: evaluate: returned a non-finite torque: nan (body id 1, t = 0 s)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  b.velocity = {1/0, 0}\nend",
       "test.lua:3: body.velocity: value must be finite, got (inf, 0)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  b:apply_impulse({0/0, 0})\nend",
       "test.lua:3: apply_impulse: impulse must be finite, got (nan, 0)"},
      {"function PopulateWorld(world)\n  world.gravity = {0, -1/0}\nend", "test.lua:2: world.gravity: "},
  };
  for (const auto& c : cases) {
    const std::string source = c[0];
    CAPTURE(source);
    std::string message;
    try {
      auto s = load(source);
      s->step();
    } catch (const SceneError& e) {
      message = e.what();
    }
    CHECK(message.starts_with(c[1]));
  }
}
