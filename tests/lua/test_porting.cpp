// The API porters from LÖVE, Box2D v3 and Chipmunk reach for (docs/porting.md), through the real
// Lua bindings, each against a closed form: a torque's angular acceleration τ/I, a conveyor
// box reaching the belt's speed at μg, a two-body gear's ratio, local anchors that are the world
// form, per-body gravity as a projectile; and the messages that point a porter at rigidlab's names.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "rigidlab/lua/scene.h"
#include "rigidlab/lua/scene_writer.h"
#include "scene_test_util.h"

using namespace rigidlab;
using lua::SceneError;
using lua_test::errorOf;
using lua_test::load;

namespace {

// Loads `source`, steps it `steps` times at its dt, runs its Check.
void runChecked(const std::string& source, int steps) {
  auto scene = load(source);
  for (int i = 0; i < steps; ++i) scene->step();
  scene->runCheck();
}

// The same scene text run under both contact solvers (the `SOLVER` placeholder).
std::vector<std::string> underBothSolvers(const std::string& source) {
  std::vector<std::string> out;
  for (const char* solver : {"sequential_impulses", "soft_step"}) {
    std::string s = source;
    s.replace(s.find("SOLVER"), 6, solver);
    out.push_back(s);
  }
  return out;
}

}  // namespace

TEST_CASE("porting: apply_torque gives the angular acceleration tau / I, apply_angular_impulse j / I") {
  // A 2 × 1 box of 3 kg: I = m (w² + h²) / 12 = 1.25 kg·m². No gravity; RK4 integrates a constant
  // torque exactly, so ω after 1 s of a 2 N·m torque is 2 / 1.25 = 1.6 rad/s and θ = ½ α t².
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, 0}, dt = 1 / 64, sleeping = false }
    local box, spun, pushed
    function PopulateWorld(world)
      box = world:add_box{ width = 2, height = 1, mass = 3 }
      check.near("inertia", box.inertia, 1.25, 1e-12)
      box:apply_torque(2, 1.0)  -- for one second
      spun = world:add_box{ width = 2, height = 1, mass = 3, position = {5, 0} }
      spun:apply_torque(2)      -- for the next step only
      pushed = world:add_box{ width = 2, height = 1, mass = 3, position = {10, 0} }
      pushed:apply_angular_impulse(0.5)
      check.near("angular impulse", pushed.angular_velocity, 0.5 / 1.25, 1e-15)
    end
    function Check(world)
      check.near("time", world.time, 2, 1e-12)
      check.near("omega after the torque stopped", box.angular_velocity, 2 / 1.25 * 1.0, 1e-12)
      check.near("angle", box.angle, 0.5 * 1.6 * 1.0 + 1.6 * 1.0, 1e-12)
      check.near("one step of torque", spun.angular_velocity, 1.6 / 64, 1e-15)
      check.near("no linear motion", box.velocity:length(), 0, 1e-15)
    end)lua",
             128);
  CHECK(errorOf(R"lua(function PopulateWorld(world) world:add_circle{ radius = 1 }:apply_torque("x") end)lua")
            .find("apply_torque: torque must be a number") != std::string::npos);
}

TEST_CASE("porting: frame helpers are the body's transform and the velocity of a point on it") {
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, 0} }
    function PopulateWorld(world)
      local b = world:add_box{ width = 2, height = 1, position = {3, 4}, angle = math.pi / 6,
                               velocity = {1, -2}, angular_velocity = 0.7 }
      local c, s = math.cos(math.pi / 6), math.sin(math.pi / 6)
      local p = b:world_point({1, 0.5})
      check.near("world_point x", p.x, 3 + c * 1 - s * 0.5, 1e-15)
      check.near("world_point y", p.y, 4 + s * 1 + c * 0.5, 1e-15)
      local back = b:local_point(p)
      check.near("local_point inverts it", (back - vec2(1, 0.5)):length(), 0, 1e-15)
      local v = b:world_vector({0, 1})
      check.near("world_vector", (v - vec2(-s, c)):length(), 0, 1e-15)
      check.near("local_vector inverts it", (b:local_vector(v) - vec2(0, 1)):length(), 0, 1e-15)
      -- v + ω × (p − c), at a world point
      local r = p - b.center
      local expected = vec2(1 - 0.7 * r.y, -2 + 0.7 * r.x)
      check.near("velocity_at", (b:velocity_at(p) - expected):length(), 0, 1e-15)
      check.that("velocity_at the centre", b:velocity_at(b.center) == b.velocity)
    end)lua",
             0);
}

TEST_CASE("porting: per-body gravity is integrated like the world's (a projectile under its own g)") {
  // Thrown from the origin at (3, 4) m/s under its own g = (1, -2) while the world's is (0, -9.8);
  // a second body scales its own g by 2; a third keeps the world's. After 1 s (RK4, exact):
  // p = v0 t + ½ g t².
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, -9.8}, dt = 1 / 50 }
    local own, scaled, plain
    function PopulateWorld(world)
      own = world:add_circle{ radius = 0.1, velocity = {3, 4}, gravity = {1, -2} }
      scaled = world:add_circle{ radius = 0.1, position = {0, 10}, velocity = {3, 4}, gravity = {1, -2}, gravity_scale = 2 }
      plain = world:add_circle{ radius = 0.1, position = {0, 20}, velocity = {3, 4} }
      check.that("gravity reads back", own.gravity == vec2(1, -2) and plain.gravity == nil)
    end
    function Check(world)
      check.near("x", own.position.x, 3 + 0.5 * 1, 1e-12)
      check.near("y", own.position.y, 4 + 0.5 * -2, 1e-12)
      check.near("vy", own.velocity.y, 4 - 2, 1e-12)
      check.near("scaled y", scaled.position.y, 10 + 4 + 0.5 * -4, 1e-12)
      check.near("scaled x", scaled.position.x, 3 + 0.5 * 2, 1e-12)
      check.near("world's y", plain.position.y, 20 + 4 - 0.5 * 9.8, 1e-12)
      plain.gravity = {0, 0}       -- a body's own gravity set at run time
      own.gravity = nil            -- and taken away again: the world's
      check.that("written", plain.gravity == vec2(0, 0) and own.gravity == nil)
    end)lua",
             50);
}

TEST_CASE("porting: a body's own gravity with every integrator, and its potential energy") {
  for (const char* integrator : {"euler", "semi_implicit_euler", "implicit_euler", "rk4"}) {
    CAPTURE(integrator);
    // Semi-implicit Euler: v_n = v0 + n h g, x_n = x0 + h Σ v_k = v0 t + g h² n (n + 1) / 2.
    runChecked(std::string(R"lua(
      local check = require "check"
      scene = { gravity = {0, -9.8}, dt = 0.1, integrator = ")lua") + integrator + R"lua(" }
      local b
      function PopulateWorld(world)
        b = world:add_circle{ radius = 0.1, mass = 2, gravity = {0, 3} }
        check.near("potential energy of its own gravity", world:potential_energy(), 0, 1e-15)
        b.position = {0, 1}
        check.near("-m g . c", world:potential_energy(), -2 * 3 * 1, 1e-12)
      end
      function Check(world)
        check.near("velocity", b.velocity.y, 3 * 1.0, 1e-12)
        local n, h = 10, 0.1
        local expected = scene.integrator == "euler" and 3 * h * h * n * (n - 1) / 2
                         or scene.integrator == "rk4" and 0.5 * 3 * 1.0
                         or 3 * h * h * n * (n + 1) / 2
        check.near("height", b.position.y - 1, expected, 1e-12)
      end)lua",
               10);
  }
}

TEST_CASE("porting: local anchors are the world anchors in each body's coordinates, on every joint that takes one") {
  // Every kind made once with world anchors and once, in another scene, with local_anchor_a and
  // local_anchor_b = body:local_point(world anchor): the two scenes stay bit for bit alike through
  // 120 steps (the core stores the same frames), and each handle reads its anchors back.
  const std::string scene = R"lua(
    local check = require "check"
    scene = { gravity = {0, -10} }
    local made = {}
    -- The anchors: one on a, and for the two-anchor kinds one on b.
    local function opts(a, b, t, two)
      local pa, pb = a:world_point({0.2, 0.1}), b:world_point({0.1, -0.05})
      if FORM == "local" then
        t.local_anchor_a, t.local_anchor_b = a:local_point(pa), b:local_point(two and pb or pa)
      elseif two then
        t.anchor_a, t.anchor_b = pa, pb
      else
        t.anchor = pa
      end
      t.a, t.b = a, b
      made[#made + 1] = {a = a, b = b, la = a:local_point(pa), lb = b:local_point(two and pb or pa)}
      return t
    end
    function PopulateWorld(world)
      local x = 0
      local function bodies()
        x = x + 10
        return world:add_box{ width = 1, height = 0.4, position = {x + 1, 3}, angle = 0.3 },
               world:add_circle{ radius = 0.3, position = {x + 2, 3.5}, angular_velocity = 1 }
      end
      local j = {}
      local a, b = bodies()
      j[#j + 1] = world:add_revolute(opts(a, b, {lower_angle = -1, upper_angle = 1}))
      a, b = bodies()
      j[#j + 1] = world:add_prismatic(opts(a, b, {axis = {1, 1}}))
      a, b = bodies()
      j[#j + 1] = world:add_distance(opts(a, b, {}, true))
      a, b = bodies()
      j[#j + 1] = world:add_weld(opts(a, b, {angular_hertz = 3}))
      a, b = bodies()
      j[#j + 1] = world:add_wheel(opts(a, b, {axis = {0, 1}, spring_hertz = 4}))
      a, b = bodies()
      j[#j + 1] = world:add_friction_joint(opts(a, b, {max_force = 5, max_torque = 1}))
      a, b = bodies()
      j[#j + 1] = world:add_motor_joint(opts(a, b, {max_force = 50, max_torque = 5}))
      a, b = bodies()
      local t = opts(a, b, {}, true)
      t.ground_a, t.ground_b = a:world_point({0.2, 5}), b:world_point({0.1, 5})
      j[#j + 1] = world:add_pulley(t)
      for i, joint in ipairs(j) do
        check.that(joint.kind .. ": local_anchor_a", joint.local_anchor_a == made[i].la, tostring(joint.local_anchor_a))
        check.that(joint.kind .. ": local_anchor_b", joint.local_anchor_b == made[i].lb, tostring(joint.local_anchor_b))
      end
    end)lua";
  auto world_form = load("FORM = 'world'\n" + scene);
  auto local_form = load("FORM = 'local'\n" + scene);
  world_form->runCheck();
  for (int i = 0; i < 120; ++i) {
    world_form->step();
    local_form->step();
  }
  const World &w = world_form->world(), &l = local_form->world();
  REQUIRE(w.bodyCount() == 16);
  bool moved = false;
  for (const BodyId id : w.bodyIds()) {
    const Body &bw = w.body(id), &bl = l.body(id);
    CAPTURE(bw.uid);
    CHECK(bw.center == bl.center);
    CHECK(bw.angle == bl.angle);
    CHECK(bw.velocity == bl.velocity);
    CHECK(bw.angular_velocity == bl.angular_velocity);
    moved = moved || std::abs(bw.angle - (bw.uid % 2 == 1 ? 0.3 : 0.0)) > 0.01;
  }
  CHECK(moved);  // the joints did work: the comparison is not of bodies at rest
}

TEST_CASE("porting: local anchors apart at creation are pulled together, one side defaults to the other, mixing is refused") {
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, 0} }
    local a, b, j, k, pin
    function PopulateWorld(world)
      -- Two capsules welded end to end although created apart (a donut of welded capsules).
      a = world:add_capsule{ a = {-1, 0}, b = {1, 0}, radius = 0.2, position = {0, 0} }
      b = world:add_capsule{ a = {-1, 0}, b = {1, 0}, radius = 0.2, position = {3, 0.5} }
      j = world:add_weld{ a = a, b = b, local_anchor_a = {1, 0}, local_anchor_b = {-1, 0} }
      -- Only a's anchor: b's is where a's is now (satisfied at creation).
      local c = world:add_circle{ radius = 0.2, position = {10, 0} }
      local d = world:add_circle{ radius = 0.2, position = {11, 0} }
      k = world:add_revolute{ a = c, b = d, local_anchor_a = {0.5, 0} }
      check.near("b's anchor follows", (k.local_anchor_b - vec2(-0.5, 0)):length(), 0, 1e-15)
      -- Pinned to the world: local_anchor_b is a world point.
      local e = world:add_box{ width = 1, height = 1, position = {20, 0} }
      pin = world:add_revolute{ a = e, local_anchor_a = {0.5, 0.5}, local_anchor_b = {20.5, 0.5} }
      check.that("pinned", pin.b == nil and pin.local_anchor_b == vec2(20.5, 0.5) and pin.local_anchor_a == vec2(0.5, 0.5))
    end
    function Check(world)
      local gap = (a:world_point({1, 0}) - b:world_point({-1, 0})):length()
      check.less("the ends are welded together", gap, 1e-3)
      check.near("and their anchors read so", (j.anchor_a - j.anchor_b):length(), gap, 1e-12)
    end)lua",
             240);
  for (const char* mixed : {"anchor = {0, 0}, local_anchor_a = {0, 0}", "anchor = {0, 0}, local_anchor_b = {0, 0}"}) {
    const std::string message = errorOf(std::string(R"lua(function PopulateWorld(world)
      local a = world:add_circle{ radius = 1 }
      world:add_revolute{ a = a, )lua") + mixed + " }\nend");
    CAPTURE(message);
    CHECK(message.find("add_revolute: anchor and local_anchor_") != std::string::npos);
    CHECK(message.find("cannot both be given") != std::string::npos);
  }
  CHECK(errorOf(R"lua(function PopulateWorld(world)
      local a, b = world:add_circle{ radius = 1 }, world:add_circle{ radius = 1, position = {3, 0} }
      world:add_distance{ a = a, b = b, anchor_a = {0, 0}, local_anchor_b = {0, 0} }
    end)lua")
            .find("add_distance: anchor_a and local_anchor_b cannot both be given") != std::string::npos);
  CHECK(errorOf(R"lua(function PopulateWorld(world)
      world:add_distance{ a = world:add_circle{ radius = 1 }, local_anchor_a = {0, 0} }
    end)lua")
            .find("add_distance: local_anchor_b is required") != std::string::npos);
}

TEST_CASE("porting: a gear of two bodies keeps angle_a + ratio * angle_b, and its ratio can change") {
  // Two wheels pinned to the world, the first driven by its pin's motor: the gear turns the second
  // backwards at half its speed (ratio 2). At t = 1 s the ratio becomes -1 (they turn alike).
  for (const char* solver : {"sequential_impulses", "auto"}) {
    CAPTURE(solver);
    runChecked(std::string(R"lua(
      local check = require "check"
      scene = { gravity = {0, -10}, solver = ")lua") + solver + R"lua(" }
      local a, b, gear, worst, constant = nil, nil, nil, 0, 0
      function PopulateWorld(world)
        a = world:add_circle{ radius = 1, position = {0, 0} }
        b = world:add_circle{ radius = 0.5, position = {3, 0}, angle = 0.25 }
        world:add_revolute{ a = a, anchor = {0, 0}, motor_speed = 1, max_motor_torque = 1000 }
        world:add_revolute{ a = b, anchor = {3, 0} }
        gear = world:add_gear{ a = a, b = b, ratio = 2 }
        check.that("a gear of bodies", gear.a == a and gear.b == b and gear.joint_a == nil and gear.ratio == 2)
        constant = a.angle + 2 * b.angle
      end
      function OnStep(world)
        worst = math.max(worst, math.abs(a.angle + gear.ratio * b.angle - constant))
        if math.abs(world.time - 1) < 1e-9 then
          gear.ratio = -1
          constant = a.angle - b.angle
        end
      end
      function Check(world)
        check.less("angle_a + ratio angle_b stays", worst, 1e-9)
        check.near("b turns as a does", b.angular_velocity, a.angular_velocity, 1e-9)
        check.near("a turns at its motor's speed", a.angular_velocity, 1, 1e-9)
      end)lua",
               120);
  }
  CHECK(errorOf(R"lua(function PopulateWorld(world)
      local a = world:add_circle{ radius = 1 }
      local j = world:add_revolute{ a = a, anchor = {0, 0} }
      world:add_gear{ a = a, joint_a = j, joint_b = j }
    end)lua")
            .find("add_gear: joint_a and a cannot both be given") != std::string::npos);
  CHECK(errorOf(R"lua(function PopulateWorld(world) world:add_gear{ a = world:add_circle{ radius = 1 } } end)lua")
            .find("add_gear: b is required") != std::string::npos);
}

TEST_CASE("porting: a box on a conveyor reaches the belt's speed at mu g, under both contact solvers") {
  // A static floor whose top runs at 2 m/s towards +x (tangent_speed > 0: clockwise around the
  // shape), friction 0.5 both: the box slides, friction accelerates it at μ g = 5 m/s² until it
  // moves with the belt at 0.4 s, then static friction carries it.
  for (const std::string& source : underBothSolvers(R"lua(
      local check = require "check"
      scene = { gravity = {0, -10}, solver = "SOLVER" }
      local box, floor, at
      function PopulateWorld(world)
        floor = world:add_box{ static = true, width = 40, height = 1, position = {0, -0.5}, friction = 0.5, tangent_speed = 2 }
        box = world:add_box{ width = 1, height = 1, position = {0, 0.5}, friction = 0.5 }
        check.that("tangent_speed reads back", floor.shapes[1].tangent_speed == 2)
      end
      function OnStep(world)
        if math.abs(world.time - 0.25) < 1e-9 then at = box.velocity.x end
      end
      function Check(world)
        check.near("speed at 0.25 s: mu g t", at, 5 * 0.25, 0.03)
        check.near("the belt's speed", box.velocity.x, 2, 1e-3)
        check.near("no sideways drift of the surface's direction", box.velocity.y, 0, 1e-3)
      end)lua")) {
    CAPTURE(source);
    runChecked(source, 60);
  }
  // Written at run time; the other direction; and in a pre_solve function for one step at a time.
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, -10} }
    local box, plain
    function PopulateWorld(world)
      local floor = world:add_box{ static = true, width = 40, height = 1, position = {0, -0.5} }
      floor.shapes[1].tangent_speed = -1.5
      box = world:add_box{ width = 1, height = 1, position = {0, 0.5} }
      local other = world:add_box{ static = true, width = 40, height = 1, position = {0, 9.5} }
      other.shapes[1].pre_solve = function(c) c.tangent_speed = 0.5 end
      plain = world:add_box{ width = 1, height = 1, position = {0, 10.5} }
    end
    function Check(world)
      check.near("runs towards -x", box.velocity.x, -1.5, 1e-3)
      check.near("pre_solve's belt", plain.velocity.x, 0.5, 1e-3)
    end)lua",
             120);
}

TEST_CASE("porting: rolling resistance slows a rolling disc at 2/3 c g, under both contact solvers") {
  // A uniform disc (I = ½ m r²) rolling without slipping at 3 m/s, resisted by a torque c r N:
  // dv/dt = −c g m r² / (I + m r²) = −⅔ c g = −2/3 m/s² for c = 0.1, g = 10.
  for (const std::string& source : underBothSolvers(R"lua(
      local check = require "check"
      scene = { gravity = {0, -10}, solver = "SOLVER" }
      local disc, plain
      function PopulateWorld(world)
        world:add_box{ static = true, width = 100, height = 1, position = {0, -0.5} }
        disc = world:add_circle{ radius = 0.5, position = {0, 0.5}, velocity = {3, 0}, angular_velocity = -6,
                                 rolling_resistance = 0.1 }
        plain = world:add_circle{ radius = 0.5, position = {0, 5.5}, velocity = {3, 0}, angular_velocity = -6 }
        world:add_box{ static = true, width = 100, height = 1, position = {0, 4.5} }
        check.that("reads back", disc.shapes[1].rolling_resistance == 0.1)
      end
      function Check(world)
        -- Against the same disc without it (which the solver's own losses slow by about 1 mm/s).
        check.near("slowed by 2/3 c g t", plain.velocity.x - disc.velocity.x, 2 / 3 * 1, 0.01)
        check.near("still rolling", disc.angular_velocity * 0.5, -disc.velocity.x, 0.01)
        check.near("without it, hardly slowed", plain.velocity.x, 3, 0.005)
      end)lua")) {
    CAPTURE(source);
    runChecked(source, 60);
  }
}

TEST_CASE("porting: pre_solve may change a contact's friction, restitution and tangent speed for that step") {
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, -10} }
    local slider, stopped, ball, seen
    function PopulateWorld(world)
      -- Frictionless for the slider only (its floor asks), while the other box stops.
      local ice = world:add_box{ static = true, width = 40, height = 1, position = {0, -0.5}, friction = 0.5 }
      ice.shapes[1].pre_solve = function(c)
        seen = c
        check.that("the shapes' mix", math.abs(c.friction - 0.5) < 1e-12 and c.restitution == 0 and c.tangent_speed == 0)
        c.friction = 0
      end
      slider = world:add_box{ width = 1, height = 1, position = {0, 0.5}, velocity = {2, 0}, friction = 0.5 }
      world:add_box{ static = true, width = 40, height = 1, position = {0, 9.5}, friction = 0.5 }
      stopped = world:add_box{ width = 1, height = 1, position = {0, 10.5}, velocity = {2, 0}, friction = 0.5 }
      -- A plastic ball made perfectly elastic for each contact.
      local pad = world:add_box{ static = true, width = 4, height = 1, position = {50, -0.5} }
      pad.shapes[1].pre_solve = function(c) c.restitution = 1 end
      ball = world:add_circle{ radius = 0.25, position = {50, 2.25} }
    end
    local highest_after_bounce, bounced = 0, false
    function OnStep(world)
      if ball.velocity.y > 0 then bounced = true end
      if bounced then highest_after_bounce = math.max(highest_after_bounce, ball.position.y) end
    end
    function Check(world)
      check.near("frictionless: keeps its speed", slider.velocity.x, 2, 1e-9)
      check.near("the other stops", stopped.velocity.x, 0, 1e-9)
      check.that("bounced", bounced)
      check.near("back to its height", highest_after_bounce, 2.25, 0.05)
      check.that("the table has the manifold's points", #seen.points == 2 and seen.points[1].separation ~= nil)
    end)lua",
             120);
  // A bad value is an error of the pre_solve function, naming the field.
  const std::string message = errorOf(R"lua(function PopulateWorld(world)
      local floor = world:add_box{ static = true, width = 4, height = 1, position = {0, -0.5} }
      floor.shapes[1].pre_solve = function(c) c.friction = -1 end
      world:add_box{ width = 1, height = 1, position = {0, 0.5} }
    end)lua",
                                      3);
  CAPTURE(message);
  CHECK(message.find("pre_solve: contact.friction must be >= 0, got -1") != std::string::npos);
}

TEST_CASE("porting: user_data on shapes and joints, kept after a break, not inherited by a reused slot") {
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, -10} }
    local shape, joint, broke_with
    function PopulateWorld(world)
      local body = world:add_body{ position = {0, 5} }
      shape = body:add_shape{ shape = "circle", radius = 0.5, user_data = {tag = "wheel"} }
      check.that("shape option", shape.user_data.tag == "wheel")
      shape.user_data = "hub"
      check.that("shape field", shape.user_data == "hub")
      local other = body:add_shape{ shape = "box", width = 1, height = 1, offset = {2, 0} }
      check.that("none given", other.user_data == nil)
      other:remove()
      local again = body:add_shape{ shape = "box", width = 1, height = 1, offset = {2, 0} }
      check.that("a new shape in the slot starts without", again.user_data == nil)
      joint = world:add_revolute{ a = body, anchor = {0, 5}, break_force = 1, user_data = "fragile" }
      check.that("joint option", joint.user_data == "fragile")
      joint.user_data = {why = "fragile"}
    end
    function OnJointBreak(world, j) broke_with = j.user_data end
    function Check(world)
      check.that("broke", joint.broken and broke_with and broke_with.why == "fragile")
      check.that("still readable after the break", joint.user_data.why == "fragile")
    end)lua",
             10);
}

TEST_CASE("porting: world:contacts() lists the touching contacts with their points") {
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, -10} }
    function PopulateWorld(world)
      world:add_box{ static = true, width = 20, height = 1, position = {0, -0.5} }
      for i = 1, 3 do world:add_box{ width = 1, height = 1, position = {3 * i, 0.5} } end
      world:add_circle{ radius = 0.5, position = {0, 10}, gravity_scale = 0 }  -- in the air: no contact
    end
    function Check(world)
      local contacts = world:contacts()
      check.that("three touching", #contacts == 3, tostring(#contacts))
      for _, c in ipairs(contacts) do
        check.that("touching", c.touching)
        check.that("two points each", #c.points == 2)
        local sum = 0
        for _, p in ipairs(c.points) do
          sum = sum + p.normal_impulse
          check.less("resting: separation", math.abs(p.separation), 0.02)
        end
        check.near("the points' impulses add to the total", sum, c.normal_impulse, 1e-12)
        check.near("weight over a step", c.normal_impulse, 1 * 10 / 60, 1e-6)
        check.near("the middle point", c.point.x, (c.points[1].point.x + c.points[2].point.x) / 2, 1e-12)
      end
    end)lua",
             120);
}

TEST_CASE("porting: ShouldCollide is asked once per pair while their boxes overlap; false lets them pass") {
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, -10} }
    local floor, ghost, solid, asked = nil, nil, nil, {}
    function ShouldCollide(a, b)
      local other = a.body == floor and b.body or a.body
      asked[other] = (asked[other] or 0) + 1
      return other ~= ghost
    end
    function PopulateWorld(world)
      floor = world:add_box{ static = true, width = 20, height = 1, position = {0, -0.5} }
      ghost = world:add_circle{ radius = 0.5, position = {0, 3} }
      solid = world:add_circle{ radius = 0.5, position = {5, 3} }
    end
    function Check(world)
      check.less("the ghost fell through", ghost.position.y, -3)
      check.near("the other rests", solid.position.y, 0.5, 0.01)
      check.that("each asked once", asked[ghost] == 1 and asked[solid] == 1,
                 tostring(asked[ghost]) .. ", " .. tostring(asked[solid]))
    end)lua",
             120);
}

TEST_CASE("porting: length, ratio, inertia and sleeping_allowed change at run time") {
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, -10} }
    local rod, bob, spinner, awake, sleeper, pulley, left, right
    function PopulateWorld(world)
      bob = world:add_circle{ radius = 0.1, position = {0, 8} }
      rod = world:add_distance{ a = bob, anchor_b = {0, 10} }
      check.near("length", rod.length, 2, 1e-12)
      rod.length = 3
      spinner = world:add_box{ width = 1, height = 1, position = {20, 20}, gravity_scale = 0 }
      spinner.inertia = 2
      spinner:apply_torque(4, 1)
      awake = world:add_box{ width = 1, height = 1, position = {30, 0.5}, sleeping_allowed = false }
      sleeper = world:add_box{ width = 1, height = 1, position = {32, 0.5} }
      world:add_box{ static = true, width = 10, height = 1, position = {31, -0.5} }
      left = world:add_box{ width = 0.5, height = 0.5, position = {40, 5}, mass = 1 }
      right = world:add_box{ width = 0.5, height = 0.5, position = {44, 5}, mass = 1 }
      pulley = world:add_pulley{ a = left, b = right, ground_a = {40, 10}, ground_b = {44, 10} }
      check.near("pulley constant", pulley.length, 10, 1e-12)
      pulley.ratio = 2      -- the ropes as they are: the constant follows
      check.near("new constant", pulley.length, 5 + 2 * 5, 1e-12)
    end
    function Check(world)
      check.near("the rod's new length", (bob.position - vec2(0, 10)):length(), 3, 1e-3)
      check.near("tau / I with the written inertia", spinner.angular_velocity, 4 / 2 * 1, 1e-9)
      check.that("not allowed to sleep", awake.awake and not awake.sleeping_allowed)
      check.that("the other sleeps", not sleeper.awake)
      check.near("ropes", pulley.length_a + 2 * pulley.length_b, pulley.length, 1e-3)
    end)lua",
             120);
}

TEST_CASE("porting: shape queries (test_point, ray_cast, bounds, distance) and motor readings") {
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, -10} }
    local arm, slider, hinge, rail
    function PopulateWorld(world)
      local disc = world:add_circle{ static = true, radius = 1, position = {2, 0} }
      local s = disc.shapes[1]
      check.that("inside", s:test_point({2.5, 0}) and not s:test_point({3.5, 0}))
      local hit = s:ray_cast{ from = {-5, 0}, to = {5, 0} }
      check.near("fraction", hit.fraction, 0.6, 1e-12)
      check.that("hit", hit.point == vec2(1, 0) and hit.normal == vec2(-1, 0) and hit.shape == s and hit.body == disc)
      local same = world:ray_cast{ from = {-5, 0}, to = {5, 0} }
      check.that("as world:ray_cast", same.fraction == hit.fraction and same.point == hit.point and same.shape == hit.shape)
      check.that("misses", s:ray_cast{ from = {-5, 3}, to = {5, 3} } == nil)
      check.that("bounds", s.bounds.lower == vec2(1, -1) and s.bounds.upper == vec2(3, 1))
      local far = world:add_circle{ static = true, radius = 1, position = {6, 0} }
      local d, on_s, on_far = s:distance(far.shapes[1])
      check.near("distance", d, 2, 1e-12)
      check.that("closest points", (on_s - vec2(3, 0)):length() < 1e-12 and (on_far - vec2(5, 0)):length() < 1e-12)
      -- A 2 kg arm held level by its pin's motor: the motor's torque is m g L = 2 · 10 · 1.
      arm = world:add_box{ width = 2, height = 0.1, position = {21, 10}, mass = 2 }
      hinge = world:add_revolute{ a = arm, anchor = {20, 10}, motor_speed = 0, max_motor_torque = 1000 }
      -- A 3 kg block held by a vertical slider's motor: its force is m g.
      slider = world:add_box{ width = 0.5, height = 0.5, position = {30, 10}, mass = 3 }
      rail = world:add_prismatic{ a = slider, anchor = {30, 10}, axis = {0, 1}, motor_speed = 0, max_motor_force = 1000 }
      check.that("axis", rail.axis == vec2(0, 1))
    end
    function Check(world)
      check.near("motor torque", math.abs(hinge.motor_torque), 20, 1e-3)
      check.near("motor force", math.abs(rail.motor_force), 30, 1e-3)
      check.near("level", arm.angle, 0, 1e-3)
    end)lua",
             60);
}

TEST_CASE("porting: shape geometry is writable (LÖVE's setRadius, setPoint; chains' neighbours)") {
  runChecked(R"lua(
    local check = require "check"
    scene = { gravity = {0, 0} }
    function PopulateWorld(world)
      local b = world:add_circle{ radius = 1, mass = 2 }
      local s = b.shapes[1]
      s.radius = 2
      check.near("the mass follows the area at the same density", b.mass, 8, 1e-12)
      s.center = {1, 0}
      check.that("centre", s.center == vec2(1, 0) and (b.local_center - vec2(1, 0)):length() < 1e-15)
      local poly = world:add_polygon{ vertices = {{0, 0}, {1, 0}, {0, 1}} }
      poly.shapes[1].vertices = {{0, 0}, {2, 0}, {0, 2}}
      check.near("area", poly.shapes[1].area, 2, 1e-12)
      local chain = world:add_chain{ points = {{0, 0}, {1, 0}, {2, 0}} }
      local first = chain.shapes[1]
      check.that("neighbours", first.ghost1 == vec2(0, 0) and first.ghost2 == vec2(2, 0))
      first.ghost1 = {-1, 0}
      check.that("written", first.ghost1 == vec2(-1, 0))
      local ok, message = pcall(function() poly.shapes[1].radius = 1 end)
      check.that("a polygon has no radius", not ok and message:find("a polygon has no radius to set", 1, true), message)
      ok, message = pcall(function() s.vertices = {{0, 0}, {1, 0}, {0, 1}} end)
      check.that("a circle has no vertices", not ok and message:find("a circle has no vertices to set", 1, true), message)
    end)lua",
             0);
}

TEST_CASE("porting: a contact hook no shape can raise gets a warning naming the option") {
  std::vector<std::string> lines;
  lua::SceneOptions options;
  options.log = [&](const std::string& line) { lines.push_back(line); };
  load(R"lua(
    function PopulateWorld(world)
      world:add_box{ static = true, width = 20, height = 1, position = {0, -0.5} }
      world:add_circle{ radius = 0.5, position = {0, 3} }
    end
    function OnContactBegin(world, c) end
    function OnHit(world, c) end)lua",
       options);
  REQUIRE(lines.size() == 2);
  CHECK(lines[0].find("warning: OnContactBegin is defined, but no shape has contact_events = true") != std::string::npos);
  CHECK(lines[1].find("warning: OnHit is defined, but no shape has hit_events = true") != std::string::npos);
  lines.clear();
  load(R"lua(
    function PopulateWorld(world) world:add_circle{ radius = 0.5, contact_events = true } end
    function OnContactBegin(world, c) end)lua",
       options);
  CHECK(lines.empty());
}

TEST_CASE("porting: LÖVE's and Box2D's names are answered with rigidlab's") {
  const auto message = [](const std::string& body) {
    return errorOf("function PopulateWorld(world)\n local a = world:add_circle{ radius = 1 }\n local b = "
                   "world:add_circle{ radius = 1, position = {3, 0} }\n" +
                   body + "\nend");
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"world:add_distance{ a = a, b = b, frequency = 4 }",
       "add_distance: unknown option 'frequency' (rigidlab calls it 'spring_hertz')"},
      {"world:add_distance{ a = a, b = b, dampingRatio = 0.5 }",
       "add_distance: unknown option 'dampingRatio' (rigidlab calls it 'spring_damping')"},
      {"world:add_motor_joint{ a = a, target = {1, 1} }",
       "add_motor_joint: unknown option 'target' (rigidlab calls it 'linear_offset')"},
      {"world:add_weld{ a = a, b = b, anchor = {1, 0}, frequency = 3 }",
       "add_weld: unknown option 'frequency' (rigidlab calls it 'angular_hertz')"},
      {"world:add_revolute{ a = a, b = b, localAnchorA = {1, 0} }",
       "add_revolute: unknown option 'localAnchorA' (rigidlab calls it 'local_anchor_a')"},
      {"a:applyTorque(1)", "body: has no field 'applyTorque' (rigidlab calls it 'apply_torque')"},
      {"a:getWorldPoint(0, 0)", "body: has no field 'getWorldPoint' (rigidlab calls it 'world_point')"},
      {"a:setLinearVelocity(1, 0)", "body: has no field 'setLinearVelocity' (rigidlab calls it 'velocity')"},
      {"a:ApplyLinearImpulse({1, 0})", "body: has no field 'ApplyLinearImpulse' (rigidlab calls it 'apply_impulse')"},
      {"local x = a.isBullet", "body: has no field 'isBullet' (rigidlab calls it 'bullet')"},
      {"local x = a.b2Body_GetPosition", "body: has no field 'b2Body_GetPosition' (rigidlab calls it 'position')"},
      {"a:getFixtures()", "body: has no field 'getFixtures' (rigidlab calls it 'shapes')"},
      {"world:translateOrigin(1, 0)",
       "world: has no field 'translateOrigin' (rigidlab has no origin shift: positions are doubles"},
      {"world:setContactFilter(print)", "world: has no field 'setContactFilter' (define the scene hook ShouldCollide"},
      {"world:getBodyCount()", "world: has no field 'getBodyCount' (rigidlab calls it 'bodies')"},
      {"a:destroy()", "body: has no field 'destroy' (remove it with world:remove(...)"},
      {"a.shapes[1]:getBoundingBox()", "shape: has no field 'getBoundingBox' (rigidlab calls it 'bounds')"},
      {"a.shapes[1]:setRestitution(1)", "shape: has no field 'setRestitution' (rigidlab calls it 'restitution')"},
      {"world:add_revolute{ a = a, anchor = {0, 0} }:getJointAngle()",
       "revolute joint: has no field 'getJointAngle' (rigidlab calls it 'angle')"},
      {"world:add_revolute{ a = a, anchor = {0, 0} }:getMotorTorque()",
       "revolute joint: has no field 'getMotorTorque' (rigidlab calls it 'motor_torque')"},
      // Typos still get their suggestion.
      {"world:add_distance{ a = a, b = b, lenght = 1 }", "add_distance: unknown option 'lenght' (did you mean 'length'?)"},
  };
  for (const auto& [code, expected] : cases) {
    const std::string m = message(code);
    CAPTURE(code);
    CAPTURE(m);
    CHECK(m.find(expected) != std::string::npos);
  }
}

TEST_CASE("porting: a saved world keeps own gravity, sleeping_allowed, surfaces and a gear of two bodies") {
  auto original = load(R"lua(
    function PopulateWorld(world)
      world:add_box{ static = true, width = 20, height = 1, position = {0, -0.5}, tangent_speed = 1.5 }
      local ball = world:add_circle{ radius = 0.5, position = {0, 0.5}, gravity = {0, -3}, sleeping_allowed = false,
                                     rolling_resistance = 0.2 }
      ball:add_shape{ shape = "box", width = 0.2, height = 0.2, offset = {0.5, 0}, tangent_speed = -1 }
      local a = world:add_circle{ radius = 1, position = {5, 5} }
      local b = world:add_circle{ radius = 0.5, position = {8, 5} }
      world:add_revolute{ a = a, anchor = {5, 5} }
      world:add_revolute{ a = b, anchor = {8, 5} }
      world:add_gear{ a = a, b = b, ratio = 2 }
    end)lua");
  const std::string saved = lua::sceneSource(original->world(), original->settings());
  CAPTURE(saved);
  auto loaded = load(saved);
  const World &o = original->world(), &l = loaded->world();
  REQUIRE(l.bodyCount() == o.bodyCount());
  REQUIRE(l.jointIds().size() == o.jointIds().size());
  const std::vector<BodyId> ob = o.bodyIds(), lb = l.bodyIds();
  for (size_t i = 0; i < ob.size(); ++i) {
    const Body &x = o.body(ob[i]), &y = l.body(lb[i]);
    CHECK(x.own_gravity == y.own_gravity);
    CHECK(x.gravity == y.gravity);
    CHECK(x.sleeping_allowed == y.sleeping_allowed);
    REQUIRE(x.shapes.size() == y.shapes.size());
    for (size_t k = 0; k < x.shapes.size(); ++k) {
      CHECK(o.shape(x.shapes[k]).tangent_speed == l.shape(y.shapes[k]).tangent_speed);
      CHECK(o.shape(x.shapes[k]).rolling_resistance == l.shape(y.shapes[k]).rolling_resistance);
    }
  }
  const JointDef& gear = l.joint(l.jointIds().back());
  CHECK(gear.type == JointType::Gear);
  CHECK(gear.joint_a.isNull());
  CHECK(gear.ratio == 2.0);
  for (int i = 0; i < 60; ++i) {
    original->step();
    loaded->step();
  }
  for (size_t i = 0; i < ob.size(); ++i) CHECK(o.body(ob[i]).center == l.body(lb[i]).center);
}

namespace {

std::filesystem::path sourceDirectory() { return std::filesystem::canonical(lua::scriptsDirectory()).parent_path(); }

std::vector<std::string> linesOf(const std::filesystem::path& file) {
  std::ifstream in(file);
  REQUIRE_MESSAGE(in, "cannot open " << file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The rows `| \`name\` | equivalent |` of the section of docs/porting.md that starts with the line
// `heading`, up to the next "## " heading: name → equivalent.
std::map<std::string, std::string> tableRows(const std::vector<std::string>& doc, const std::string& heading) {
  std::map<std::string, std::string> rows;
  bool in = false;
  for (const std::string& line : doc) {
    if (line.starts_with("## ")) in = line == heading;
    if (!in || !line.starts_with("| `")) continue;
    const size_t close = line.find('`', 3);
    REQUIRE(close != std::string::npos);
    const std::string name = line.substr(3, close - 3);
    CHECK_MESSAGE(rows.count(name) == 0, name << " is listed twice");
    rows[name] = line.substr(close + 1);
  }
  return rows;
}

}  // namespace

TEST_CASE("porting: docs/porting.md has a row for every love.physics and Box2D v3.1 function; love.physics coverage >= 95 %") {
  const std::vector<std::string> doc = linesOf(sourceDirectory() / "docs" / "porting.md");
  struct Table {
    const char* heading;
    const char* names;  // tests/lua/data: one name a line
  };
  for (const Table& t : {Table{"## love.physics → rigidlab", "love_physics_11_5.txt"}, Table{"## Box2D v3 → rigidlab", "box2d_v3_1.txt"}}) {
    CAPTURE(t.heading);
    const std::map<std::string, std::string> rows = tableRows(doc, t.heading);
    const std::vector<std::string> names = linesOf(sourceDirectory() / "tests" / "lua" / "data" / t.names);
    for (const std::string& name : names) CHECK_MESSAGE(rows.count(name) == 1, name << " has no row");
    CHECK(rows.size() == names.size());
    size_t none = 0;
    for (const auto& [name, equivalent] : rows) {
      CAPTURE(name);
      const bool lacks = equivalent.find("**none**") != std::string::npos && equivalent.find("**none**") < 4;
      none += lacks;
      CHECK(equivalent.size() > 8);  // something is said
    }
    const double coverage = 1.0 - static_cast<double>(none) / static_cast<double>(names.size());
    MESSAGE(std::string(t.heading) << ": " << names.size() - none << " of " << names.size() << " have an equivalent (" << 100 * coverage << " %)");
    if (std::string(t.names).starts_with("love")) CHECK(coverage >= 0.95);
  }
}
