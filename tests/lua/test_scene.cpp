// The Lua layer: Lua forces at every integrator stage, no Lua calls when a scene has no Lua
// forces, determinism, sandbox limits, and one clean message for every kind of scene mistake.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "rigidlab/lua/scene.h"
#include "scene_test_util.h"

using namespace rigidlab;
using rigidlab::lua::Scene;
using rigidlab::lua::SceneError;

namespace {

using lua_test::errorOf;
using lua_test::load;

// Oscillator k = 4π², m = 1, x0 = 0.1 with the spring written in Lua; L∞ position error over the
// 0.1 s grid up to 10.1 s, relative to x0.
double luaOscillatorError(double dt) {
  auto scene = load(R"lua(
    scene = { gravity = {0, 0}, integrator = "rk4" }
    function PopulateWorld(world)
      local b = world:add_circle{ name = "b", radius = 0.05, mass = 1, position = {0.1, 0} }
      local k = 4 * math.pi ^ 2
      world:add_force{ body = b, evaluate = function(s) return -k * s.position.x, -k * s.position.y end }
    end)lua");
  const BodyId b = *scene->world().findBody(std::string_view("b"));
  const long per_sample = std::lround(0.1 / dt);
  double err = 0;
  for (int sample = 1; sample <= 101; ++sample) {
    for (long i = 0; i < per_sample; ++i) scene->step(dt);
    const double t = sample * 0.1;
    err = std::max(err, std::abs(scene->world().body(b).center.x() - 0.1 * std::cos(2 * std::numbers::pi * t)) / 0.1);
  }
  return err;
}

// A scene that fails: loaded (and stepped `steps` times), it must end with one line that starts
// with `message`.
struct Case {
  const char* source;
  int steps;
  const char* message;
};

void checkMessages(const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    CAPTURE(c.source);
    const std::string message = errorOf(c.source, c.steps);
    // One line, starting with the expected text (require's message goes on to list the folders).
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.substr(0, std::string(c.message).size()) == c.message);
  }
}

}  // namespace

TEST_CASE("a scene without Lua forces makes no call into Lua during a step") {
  auto scene = load(R"lua(
    function PopulateWorld(world)
      world:add_box{ width = 20, height = 1, position = {0, -0.5}, static = true }
      local b = world:add_circle{ radius = 0.5, position = {0, 3} }
      world:add_spring{ a = b, anchor = {0, 6}, stiffness = 20, damping = 0.1 }
      world:add_damper{ body = b, coefficient = 0.2 }
    end
    function Check(world) end)lua");
  const long before = scene->luaCalls();
  for (int i = 0; i < 120; ++i) scene->step();
  CHECK(scene->luaCalls() == before);
  scene->runCheck();
  CHECK(scene->luaCalls() == before + 1);
}

TEST_CASE("a Lua force is called at every integrator stage: 4 per RK4 step, 1 per Euler step") {
  auto scene = load(R"lua(
    scene = { integrator = "rk4", dt = 0.1 }
    times = {}
    function PopulateWorld(world)
      local b = world:add_circle{ radius = 0.5 }
      world:add_force{ body = b, evaluate = function(s) times[#times + 1] = s.time return 0, 0 end }
    end
    function Check(world)
      -- RK4 stage times of the first step: t, t + h/2, t + h/2, t + h
      local expected = {0, 0.05, 0.05, 0.1}
      for i = 1, 4 do
        if math.abs(times[i] - expected[i]) > 1e-15 then error("stage " .. i .. " at t = " .. times[i]) end
      end
    end)lua");
  const long before = scene->luaCalls();
  scene->step();
  CHECK(scene->luaCalls() - before == 4);
  scene->runCheck();
  scene->world().setIntegrator(Integrator::SemiImplicitEuler);
  const long mid = scene->luaCalls();
  scene->step();
  CHECK(scene->luaCalls() - mid == 1);
}

TEST_CASE("a Lua force keeps RK4 fourth order (evaluated on each stage's state)") {
  std::vector<double> dts, errs;
  for (int k = 0; k <= 3; ++k) {
    dts.push_back(1.0 / (30.0 * std::pow(2.0, k)));
    errs.push_back(luaOscillatorError(dts.back()));
  }
  const double order = std::log(errs.front() / errs.back()) / std::log(dts.front() / dts.back());
  MESSAGE("RK4 with a Lua force: order " << order);
  CHECK(order == doctest::Approx(4.0).epsilon(0.075));
}

TEST_CASE("runs are deterministic: math.random is seeded by the host, body order follows creation") {
  const std::string source = R"lua(
    function PopulateWorld(world)
      world:add_box{ width = 30, height = 1, position = {0, -0.5}, static = true }
      local names = { alpha = 1, beta = 2, gamma = 3, delta = 4, epsilon = 5 }
      local sorted = {}
      for name in pairs(names) do sorted[#sorted + 1] = name end
      table.sort(sorted)  -- pairs() order varies between runs; sorting makes creation order fixed
      for _, name in ipairs(sorted) do
        world:add_circle{ name = name, radius = 0.3 + 0.2 * math.random(), position = {math.random(-5, 5), 2 + 3 * math.random()} }
      end
    end)lua";
  const auto run = [&] {
    auto scene = load(source);
    for (int i = 0; i < 200; ++i) scene->step();
    std::vector<double> state;
    for (BodyId id : scene->world().bodyIds()) {
      const Body& b = scene->world().body(id);
      state.insert(state.end(), {b.center.x(), b.center.y(), b.angle, b.velocity.x(), b.velocity.y()});
    }
    return state;
  };
  const auto first = run(), second = run();
  REQUIRE(first.size() == 6 * 5);
  CHECK(first == second);  // bit-identical
}

TEST_CASE("every scene mistake is one message: file:line: function: what, with the bad value") {
  checkMessages({
      {"function PopulateWorld(world)\n  world:add_circle{ radius = -1 }\nend", 0,
       "test.lua:2: add_circle: radius must be > 0, got -1"},
      {"function PopulateWorld(world)\n  world:add_box{ widht = 1, height = 2 }\nend", 0,
       "test.lua:2: add_box: unknown option 'widht' (did you mean 'width'?)"},
      {"function PopulateWorld(world)\n  world:add_circle{ radius = 'big' }\nend", 0,
       "test.lua:2: add_circle: radius must be a number, got \"big\""},
      {"function PopulateWorld(world)\n  world:add_circle{ radius = 1, position = {0/0, 1} }\nend", 0,
       "test.lua:2: add_circle: position must be finite, got (nan, 1)"},
      {"function PopulateWorld(world)\n  world:add_circle{ radius = 1, density = 2, mass = 3 }\nend", 0,
       "test.lua:2: add_circle: mass and density cannot both be given (mass sets the density)"},
      {"function PopulateWorld(world)\n  world:add_box{ width = 1, height = 1, restitution = 1.5 }\nend", 0,
       "test.lua:2: add_box: restitution must be between 0 and 1, got 1.5"},
      {"function PopulateWorld(world)\n  world:add_polygon{ vertices = {{0,0},{1,0},{1,1},{0.5,0.2},{0,1}} }\nend", 0,
       "test.lua:2: add_polygon: polygon is not convex: it turns clockwise at vertices[4] (0.5, 0.2) (give concave = "
       "true to make the body of convex pieces)"},
      {"function PopulateWorld(world)\n  world:add_polygon{ vertices = {{0,0},{1,0},'x'} }\nend", 0,
       "test.lua:2: add_polygon: vertices[3] must be a point {x, y}, got \"x\""},
      {"function PopulateWorld(world)\n  world:add_spring{ a = 5, anchor = {0, 0}, stiffness = 1 }\nend", 0,
       "test.lua:2: add_spring: a must be a body (from world:add_box, add_circle, ...), got 5"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_spring{ a = b, stiffness = 1 }\nend",
       0, "test.lua:3: add_spring: anchor is required (or b): a spring ends at a body (b) or at a fixed point (anchor)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_force{ body = b, evaluate = 3 }\nend",
       0, "test.lua:3: add_force: evaluate must be a function(s) returning fx, fy [, torque], got 3"},
      {"function PopulateWorld(world)\n  world.add_circle{ radius = 1 }\nend", 0,
       "test.lua:2: add_circle: call it as world:add_circle(...), with a colon; got a table as the world"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  print(b.postion)\nend", 0,
       "test.lua:3: body: has no field 'postion' (did you mean 'position'?)"},
      {"function PopulateWorld(world)\n  world.integrator = 'rk5'\nend", 0,
       "test.lua:2: world.integrator: must be one of euler, semi_implicit_euler, rk4, implicit_euler, got \"rk5\""},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:remove(b)\n  b.mass = 2\nend", 0,
       "test.lua:4: body.mass: body (id 1) was removed from the world"},
      {"scene = { dt = 0 }\nfunction PopulateWorld(world) end", 0, "test.lua:1: scene: dt must be > 0, got 0"},
      {"scene = {\n  title = 'x',\n  gravty = {0, 1},\n}\nfunction PopulateWorld(world) end", 0,
       "test.lua:1: scene: unknown option 'gravty' (did you mean 'gravity'?)"},
      {"scene = 5\nfunction PopulateWorld(world) end", 0, "test.lua:1: scene: must be a table of settings, got 5"},
      {"scene = {}", 0, "test.lua: PopulateWorld is not defined (a scene must define function PopulateWorld(world))"},
      {"PopulateWorld = 3", 0, "test.lua: PopulateWorld must be a function, got 3"},
      {"function PopulateWorld(world) end\nOnStep = {}", 0, "test.lua: OnStep must be a function, got a table"},
      {"function PopulateWorld(world)\n  local x = = 1\nend", 0, "test.lua:2: unexpected symbol near '='"},
      {"function PopulateWorld(world)\n  foo.bar = 1\nend", 0,
       "test.lua:2: PopulateWorld: attempt to index a nil value (global 'foo')"},
      {"function PopulateWorld(world)\n  assert(false, 'my assertion')\nend", 0, "test.lua:2: PopulateWorld: my assertion"},
      {"function PopulateWorld(world)\n  error({code = 1})\nend", 0, "test.lua:2: PopulateWorld: error object is a table"},
      {"x = nil + 1\nfunction PopulateWorld(world) end", 0, "test.lua:1: attempt to perform arithmetic on a nil value"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_force{ body = b,\n    evaluate = function(s) return 0/0, 0 end }\nend",
       1, "test.lua:4: evaluate: returned a non-finite fx: nan (body id 1, t = 0 s)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_force{ body = b, evaluate = function(s) return 1e308 * 10, 0 end }\nend",
       1, "test.lua:3: evaluate: returned a non-finite fx: inf (body id 1, t = 0 s)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_force{ body = b, evaluate = function(s) return 'x' end }\nend",
       1, "test.lua:3: evaluate: must return fx, fy [, torque] as numbers; fx is \"x\""},
      // A C function as evaluate has no line of its own: the add_force call is named.
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_force{ body = b, evaluate = math.floor }\nend",
       1, "test.lua:3: evaluate: bad argument #1 to 'math.floor' (number expected, got table)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n\n  world:add_force{ body = b,\n    evaluate = rawlen }\nend",
       1, "test.lua:4: evaluate: must return fx, fy [, torque] as numbers; fy is nil"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_force{ body = b, evaluate = function(s)\n    error('boom') end }\nend",
       1, "test.lua:4: evaluate: boom"},
      {"function PopulateWorld(world) end\nfunction OnStep(world, dt)\n  world:step(-1)\nend", 1,
       "test.lua:3: step: dt must be > 0, got -1"},
      {"function PopulateWorld(world) end\nfunction Check(world)\n  error('energy 3.2 J, expected 3.25 J')\nend", 0,
       "test.lua:3: Check: energy 3.2 J, expected 3.25 J"},
      {"function PopulateWorld(world)\n  require 'forces.sprng'\nend", 0, "test.lua:2: require: module 'forces.sprng' not found"},
      {"function PopulateWorld(world)\n  require '../etc/passwd'\nend", 0,
       "test.lua:2: require: module name must look like \"forces.spring\", got \"../etc/passwd\""},
      {"function PopulateWorld(world)\n  setmetatable({}, {__gc = function() end})\nend", 0,
       "test.lua:2: PopulateWorld: setmetatable: __gc metamethods are not allowed in scenes"},
      {"function PopulateWorld(world)\n  load('x = 1', 'chunk', 'b')\nend", 0,
       "test.lua:2: PopulateWorld: load: only text chunks can be loaded (mode \"t\"), got mode \"b\""},
      {"function PopulateWorld(world)\n  os.execute('true')\nend", 0,
       "test.lua:2: PopulateWorld: attempt to index a nil value (global 'os')"},
  });
}

TEST_CASE("shape, body type and joint mistakes are one message: file:line: function: the field and the value") {
  // Line 2 makes what line 3 uses.
  checkMessages({
      {"function PopulateWorld(world)\n  world:add_capsule{ a = {0, 0}, b = {1, 0}, radius = -1 }\nend", 0,
       "test.lua:2: add_capsule: radius must be > 0, got -1"},
      {"function PopulateWorld(world)\n  world:add_segment{ a = {0, 0}, b = {1, 0}, type = 'dynamic' }\nend", 0,
       "test.lua:2: add_segment: type \"dynamic\" is refused: a segment has no area, so only a static or kinematic "
       "body may have one (use a capsule or a thin box)"},
      {"function PopulateWorld(world)\n  world:add_chain{ points = {{0, 0}} }\nend", 0,
       "test.lua:2: add_chain: points needs at least 2 points, got 1"},
      {"function PopulateWorld(world)\n  world:add_chain{ points = {{0, 0}, 'x'} }\nend", 0,
       "test.lua:2: add_chain: points[2] must be a point {x, y}, got \"x\""},
      {"function PopulateWorld(world)\n  world:add_chain{ points = {{0, 0}, {1, 0}}, density = 2 }\nend", 0,
       "test.lua:2: add_chain: density cannot be given: a segment or chain has no area, so no density or mass"},
      {"function PopulateWorld(world)\n  world:add_box{ width = 1, height = 1, static = true, velocity = {1, 0} }\nend", 0,
       "test.lua:2: add_box: velocity must be zero for a static body, got (1, 0) (a static body cannot move: make it "
       "type = \"kinematic\" to move it by its velocity)"},
      {"function PopulateWorld(world)\n  local b = world:add_box{ width = 1, height = 1, static = true }\n  b.velocity = {0, 2}\nend",
       0, "test.lua:3: body.velocity: a static body cannot move, got (0, 2): make it kinematic (body.type = \"kinematic\") "
          "to give it a velocity"},
      {"function PopulateWorld(world)\n  world:add_circle{ radius = 1, type = 'kinetic' }\nend", 0,
       "test.lua:2: add_circle: type must be \"static\", \"kinematic\" or \"dynamic\", got \"kinetic\""},
      {"function PopulateWorld(world)\n  world:add_circle{ radius = 1, category = 0.5 }\nend", 0,
       "test.lua:2: add_circle: category must be an integer set of bits (e.g. 1 << 3, 0x8 or -1 for all 64), got 0.5"},
      {"function PopulateWorld(world)\n  world:add_circle{ radius = 1, group = 1 << 40 }\nend", 0,
       "test.lua:2: add_circle: group must be between -2147483648 and 2147483647, got 1099511627776"},
      {"function PopulateWorld(world)\n  world:add_body{ friction = 1 }\nend", 0,
       "test.lua:2: add_body: friction is an option of a shape, and add_body makes a body without shapes: give it to "
       "body:add_shape{...}"},
      {"function PopulateWorld(world)\n  local b = world:add_body{}\n  b:add_shape{ shape = 'circle', radus = 1 }\nend", 0,
       "test.lua:3: add_shape: unknown option 'radus' (did you mean 'radius'?)"},
      {"function PopulateWorld(world)\n  local b = world:add_body{}\n  b:add_shape{ radius = 1 }\nend", 0,
       "test.lua:3: add_shape: shape is required: \"circle\", \"box\", \"polygon\", \"capsule\" or \"segment\""},
      {"function PopulateWorld(world)\n  local b = world:add_body{}\n  b:add_shape{ shape = 'box', width = 1, height = 1, "
       "radius = 2 }\nend",
       0, "test.lua:3: add_shape: radius is not an option of a box shape (it takes width, height, offset and angle)"},
      {"function PopulateWorld(world)\n  local b = world:add_body{}\n  b:add_shape{ shape = 'box', width = 1, height = 1, "
       "offset = {1.7e308, 0} }\nend",
       0, "test.lua:3: add_shape: offset (1.7e+308, 0) puts the shape out of range"},
      {"function PopulateWorld(world)\n  local b = world:add_polygon{ vertices = {{0,0},{2,0},{2,1},{1,1},{1,2},{0,2}}, "
       "concave = true }\n  print(b.vertices)\nend",
       0, "test.lua:3: body.vertices: the body has 2 shapes; read body.shapes[i].vertices"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  b:set_target{ time = 1 }\nend", 0,
       "test.lua:3: set_target: moves kinematic bodies, and this one is dynamic (make it type = \"kinematic\")"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  local s = b.shapes[1]\n  s:remove()\n"
       "  world:remove(s)\nend",
       0, "test.lua:5: remove: the shape was removed (by shape:remove() or with its body)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_revolute{ a = b, anchor = "
       "{0, 0}, lower_angle = 1, upper_angle = 0 }\nend",
       0, "test.lua:3: add_revolute: lower_angle (1) must not exceed upper_angle (0)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_wheel{ a = b, anchor = "
       "{0, 0}, axis = {0, 0} }\nend",
       0, "test.lua:3: add_wheel: axis must not be zero, got (0, 0)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1, static = true }\n  world:add_weld{ a = b, "
       "anchor = {0, 0} }\nend",
       0, "test.lua:3: add_weld: a and b are both static or kinematic (a: body (id 1), static; b: the world): at least one "
          "of the joint's bodies must be dynamic (a joint between static or kinematic bodies does nothing)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_gear{ joint_a = "
       "world:add_revolute{ a = b, anchor = {0, 0} }, joint_b = world:add_weld{ a = b, anchor = {0, 0} } }\nend",
       0, "test.lua:3: add_gear: joint_b must be a revolute or prismatic joint, got a weld joint"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_distance{ a = b }\nend", 0,
       "test.lua:3: add_distance: anchor_b is required"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_weld{ a = b, anchor = {0, 0}, "
       "break_force = -1 }\nend",
       0, "test.lua:3: add_weld: break_force must be > 0, got -1"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_prismatic{ a = b, anchor = "
       "{0, 0}, axis = {1, 0}, max_motor_torque = 1 }\nend",
       0, "test.lua:3: add_prismatic: unknown option 'max_motor_torque' (did you mean 'max_motor_force'?)"},
      {"function PopulateWorld(world)\n  local j = world:add_prismatic{ a = world:add_circle{ radius = 1 }, anchor = {0, 0}, "
       "axis = {1, 0} }\n  j.upper_angle = 1\nend",
       0, "test.lua:3: prismatic joint: has no field 'upper_angle' (did you mean 'upper'?)"},
      {"function PopulateWorld(world)\n  local j = world:add_revolute{ a = world:add_circle{ radius = 1 }, anchor = {0, 0} }\n"
       "  j.motor_speed = 'fast'\nend",
       0, "test.lua:3: joint.motor_speed: must be a number, got \"fast\""},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_force{ body = b, evaluate = "
       "function(s)\n    world:add_revolute{ a = b, anchor = {0, 0} } return 0, 0 end }\nend",
       1, "test.lua:4: add_revolute: not allowed while the world is stepping (from inside a force)"},
      {"function PopulateWorld(world)\n  local b = world:add_circle{ radius = 1 }\n  world:add_force{ body = b, evaluate = "
       "function(s)\n    b.shapes[1].friction = 0 return 0, 0 end }\nend",
       1, "test.lua:4: shape.friction: not allowed while the world is stepping (from inside a force)"},
  });
}

TEST_CASE("joints count against the scene's memory limit, and removed ones are given back") {
  lua::SceneOptions options;
  options.limits.memory_bytes = size_t{8} << 20;
  options.limits.hook_seconds = 30.0;  // the memory is tested, not the time (the sanitizers on a loaded machine are slow)
  // 8 MiB hold a few thousand joints: a loop that makes joints ends with the memory message...
  std::string message;
  try {
    load("function PopulateWorld(world)\n  local a = world:add_circle{ radius = 1 }\n  local b = world:add_circle{ radius = 1, "
         "position = {3, 0} }\n  while true do world:add_weld{ a = a, b = b, anchor = {1, 0} } end\nend",
         options);
  } catch (const SceneError& e) {
    message = e.what();
  }
  CHECK(message.starts_with("test.lua:4: add_weld: not enough memory (the scene's limit is 8 MiB)"));
  // ... while one that removes what it makes runs as long as it likes.
  auto scene = load("function PopulateWorld(world)\n  local a = world:add_circle{ radius = 1 }\n  for i = 1, 20000 do\n"
                    "    world:add_weld{ a = a, anchor = {0, 0} }:remove()\n  end\nend",
                    options);
  CHECK(scene->world().jointIds().empty());
}

TEST_CASE("a broken joint's handle says broken after the step that broke it") {
  auto scene = load(R"lua(
    function PopulateWorld(world)
      local shelf = world:add_box{ width = 1, height = 0.1, position = {0.5, 0} }
      bracket = world:add_weld{ a = shelf, anchor = {0, 0}, break_force = 0.5 }  -- it weighs 0.98 N
    end
    function Check(world)
      assert(bracket.broken and bracket.removed, "not broken")
    end)lua");
  scene->step();
  CHECK(scene->world().jointIds().empty());
  scene->runCheck();
}

TEST_CASE("awake = false creates a body asleep, and reference_angle is the relative angle that counts as 0") {
  auto scene = load(R"lua(
    function PopulateWorld(world)
      world:add_box{ width = 20, height = 1, position = {0, -0.5}, static = true }
      crate = world:add_box{ width = 1, height = 1, position = {0, 0.5}, awake = false }
      awake_crate = world:add_box{ width = 1, height = 1, position = {3, 0.5} }
      -- A rod pinned at the origin, hanging straight down (angle 0) but with reference_angle 0.5:
      -- its joint angle reads -0.5, and a limit of [-0.1, 0.1] about the reference holds it there.
      rod = world:add_box{ width = 0.1, height = 2, position = {10, -1}, gravity_scale = 0 }
      pin = world:add_revolute{ a = rod, anchor = {10, 0}, reference_angle = 0.5 }
      limited = world:add_box{ width = 0.1, height = 2, position = {20, -1}, gravity_scale = 0 }
      world:add_revolute{ a = limited, anchor = {20, 0}, reference_angle = -0.3, lower_angle = -0.1, upper_angle = 0.1 }
      glued = world:add_box{ width = 1, height = 0.2, position = {30, 0}, gravity_scale = 0 }
      world:add_weld{ a = glued, anchor = {30, 0}, reference_angle = 0.2 }
      default = world:add_revolute{ a = world:add_circle{ radius = 0.5, position = {40, 0}, angle = 0.7 }, anchor = {40, 0} }
      assert(not crate.awake and awake_crate.awake, "awake option")
      assert(pin.reference_angle == 0.5 and math.abs(pin.angle + 0.5) < 1e-15, "pin angle " .. pin.angle)
      assert(default.reference_angle == 0.7 and default.angle == 0, "default reference " .. default.reference_angle)
    end
    function Check(world)
      assert(not crate.awake, "the crate was woken")
      -- The limit turns the rod from joint angle 0.3 (its angle 0, less the reference -0.3) to the
      -- limit's 0.1, its angle -0.3 + 0.1; the weld turns its body to the glued angle.
      assert(math.abs(limited.angle - (-0.3 + 0.1)) < 1e-3, "limited angle " .. limited.angle)
      assert(math.abs(glued.angle - 0.2) < 1e-3, "glued angle " .. glued.angle)
    end)lua");
  for (int i = 0; i < 120; ++i) scene->step();
  scene->runCheck();
  checkMessages({
      {"function PopulateWorld(w) w:add_box{ width = 1, height = 1, awake = 0 } end", 0,
       "test.lua:1: add_box: awake must be true or false"},
      {"function PopulateWorld(w) w:add_revolute{ a = w:add_circle{ radius = 1 }, anchor = {0, 0}, reference_angle = 0/0 } end", 0,
       "test.lua:1: add_revolute: reference_angle must be"},
      {"function PopulateWorld(w) w:add_distance{ a = w:add_circle{ radius = 1 }, anchor_b = {0, 1}, reference_angle = 1 } end", 0,
       "test.lua:1: add_distance: unknown option 'reference_angle'"},
      {"function PopulateWorld(w) local j = w:add_weld{ a = w:add_circle{ radius = 1 }, anchor = {0, 0} } j.reference_angle = 1 end", 0,
       "test.lua:1: joint.reference_angle: is read-only"},
  });
}

TEST_CASE("a Lua force that fails leaves the world as it was before the step") {
  auto scene = load(R"lua(
    function PopulateWorld(world)
      local b = world:add_circle{ name = "b", radius = 1, velocity = {1, 0} }
      world:add_force{ body = b, evaluate = function(s) if s.time > 0.05 then error("late failure") end return 0, 0 end }
    end)lua");
  scene->step();
  scene->step();
  scene->step();
  const World& w = scene->world();
  const Body before = w.body(*w.findBody(std::string_view("b")));
  const double t = w.time();
  CHECK_THROWS_AS(scene->step(), SceneError);
  CHECK(w.time() == t);
  const Body& after = w.body(*w.findBody(std::string_view("b")));
  CHECK(after.center == before.center);
  CHECK(after.velocity == before.velocity);
}

TEST_CASE("a binary chunk is refused before the parser sees it") {
  CHECK(errorOf("\x1bLua\x54\x00 garbage") == "test.lua: binary (precompiled) chunks are not allowed; load Lua source text");
}

TEST_CASE("the memory cap ends a memory bomb with a clear error, and the host survives") {
  lua::SceneOptions options;
  options.limits.memory_bytes = size_t{32} << 20;
  std::string message;
  try {
    load("function PopulateWorld(world)\n  local s = 'x'\n  while true do s = s .. s end\nend", options);
  } catch (const SceneError& e) {
    message = e.what();
  }
  CHECK(message == "test.lua:3: PopulateWorld: not enough memory (the scene's limit is 32 MiB)");  // the loop's line
  // A normal scene still loads afterwards.
  CHECK(load("function PopulateWorld(world) world:add_circle{ radius = 1 } end")->world().bodyCount() == 1);
}

TEST_CASE("require finds modules under scripts/ and beside the scene, and reports them for hot reload") {
  auto scene = load(R"lua(
    local spring = require "forces.spring"
    local again = require "forces.spring"
    assert(spring == again, "modules are loaded once")
    function PopulateWorld(world) end)lua");
  const auto files = scene->sourceFiles();
  REQUIRE(files.size() == 1);  // loadString has no file of its own; one module
  CHECK(files[0].filename() == "spring.lua");
  CHECK(files[0].parent_path().filename() == "forces");
}

TEST_CASE("print goes to the scene's log") {
  std::vector<std::string> lines;
  lua::SceneOptions options;
  options.log = [&](const std::string& line) { lines.push_back(line); };
  load("function PopulateWorld(world) print('hello', 1, vec2(1, 2), nil) end", options);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0] == "hello\t1\tvec2(1, 2)\tnil");
}

TEST_CASE("Exact(t) returns the closed-form states keyed by body name or handle") {
  auto scene = load(R"lua(
    scene = { gravity = {0, -10} }
    local ball
    function PopulateWorld(world)
      world:add_circle{ name = "a", radius = 0.5 }
      ball = world:add_circle{ radius = 0.5, position = {5, 0}, velocity = {1, 0} }
    end
    function Exact(t)
      return { a = { position = {0, -5 * t * t}, velocity = {0, -10 * t} },
               [ball] = { position = {5 + t, -5 * t * t}, angle = 0 } }
    end)lua");
  REQUIRE(scene->hasExact());
  const auto states = scene->exact(2.0);
  REQUIRE(states.size() == 2);
  CHECK(states[0].uid == 1);
  CHECK(states[0].position.y() == -20.0);
  CHECK(states[0].velocity.value().y() == -20.0);
  CHECK_FALSE(states[0].angle.has_value());
  CHECK(states[1].uid == 2);
  CHECK(states[1].position.x() == 7.0);
  CHECK(states[1].angle.value() == 0.0);
  auto bad = load("function PopulateWorld(w) end\nfunction Exact(t) return { nobody = { position = {0, 0} } } end");
  CHECK_THROWS_WITH_AS(bad->exact(0.0), "test.lua: Exact: no body is named \"nobody\"", SceneError);
}
