#include "bench_scenes.h"

#include <string>

namespace rigidlab::app {
namespace {

// 1000 discs in a 40 × 25 grid, 1 m apart (no contacts), each hanging from its own anchor on a
// spring (k = 100 N/m, c = 0.1 N·s/m, stretched 0.2 m), RK4 under gravity.
constexpr int kSpringBodies = 1000;

BenchWorld builtinSprings() {
  BenchWorld b;
  WorldDef def;
  def.integrator = Integrator::RungeKutta4;
  b.world = std::make_unique<World>(def);
  for (int i = 0; i < kSpringBodies; ++i) {
    BodyDef d;
    d.shape = makeCircle(0.1);
    d.position = Vec2(i % 40, -(i / 40) * 1.0);
    const BodyId id = b.world->createBody(d);
    SpringDef s;
    s.a = id;
    s.anchor = d.position + Vec2(0.0, 0.5);
    s.stiffness = 100.0;
    s.rest_length = 0.3;
    s.damping = 0.1;
    b.world->addSpring(s);
  }
  return b;
}

// The same scene with the springs written in Lua (scripts/forces/spring.lua).
BenchWorld luaSprings() {
  const std::string source = R"lua(
    scene = { integrator = "rk4" }
    local spring = require "forces.spring"
    function PopulateWorld(world)
      for i = 0, )lua" + std::to_string(kSpringBodies - 1) + R"lua( do
        local x, y = i % 40, -(i // 40) * 1.0
        local body = world:add_circle{ radius = 0.1, position = {x, y} }
        spring.add(world, { a = body, anchor = {x, y + 0.5}, stiffness = 100, rest_length = 0.3, damping = 0.1 })
      end
    end
  )lua";
  BenchWorld b;
  b.scene = lua::Scene::loadString(source, "bench:lua_springs");
  return b;
}

}  // namespace

const std::vector<BenchScene>& benchScenes() {
  static const std::vector<BenchScene> scenes = {
      {"springs", "1000 bodies on built-in springs, RK4, no contacts", 600, 1.0 / 60.0, builtinSprings},
      {"lua_springs", "1000 bodies on Lua springs (forces.spring), RK4, no contacts", 600, 1.0 / 60.0, luaSprings},
  };
  return scenes;
}

}  // namespace rigidlab::app
