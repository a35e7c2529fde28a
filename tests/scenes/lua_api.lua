-- The body and world API: fields, writes, methods, handles, hooks, require and sandbox limits.
local check = require "check"

scene = { title = "Lua API", gravity = {0, 0}, dt = 0.1, integrator = "semi_implicit_euler", iterations = 7,
          duration = 1 }

local steps_seen, box, ball = 0, nil, nil

function PopulateWorld(world)
  -- world fields
  check.that("world.integrator", world.integrator == "semi_implicit_euler")
  check.near("world.dt", world.dt, 0.1, 0)
  check.near("world.iterations", world.iterations, 7, 0)
  check.that("world.gravity", world.gravity == vec2(0, 0))
  check.near("world.time", world.time, 0, 0)
  check.that("world.title", world.title == "Lua API")

  box = world:add_box{ name = "box", width = 2, height = 1, position = {1, 2}, angle = 0.5, density = 3,
                       restitution = 0.25, friction = 0.4 }
  check.near("box mass (density × area)", box.mass, 6, 1e-12)
  check.near("box inertia m (w² + h²) / 12", box.inertia, 6 * 5 / 12, 1e-12)
  check.near("box density", box.density, 3, 1e-12)
  check.near("static_friction defaults to friction", box.static_friction, 0.4, 0)
  check.that("box.shape", box.shape == "polygon" and #box.vertices == 4 and box.radius == nil)
  check.that("box.center is the centroid", (box.center - vec2(1, 2)):length() < 1e-12)
  check.that("box.static", box.static == false)
  check.that("ids count from 1", box.id == 1)

  ball = world:add_circle{ name = "ball", radius = 0.5, mass = 2, position = {5, 0} }
  check.near("ball mass", ball.mass, 2, 0)
  check.near("ball inertia ½ m r²", ball.inertia, 0.25, 1e-15)
  check.that("find returns the same handle", world:find("ball") == ball and rawequal(world:find("ball"), ball))
  check.that("find of a missing name is nil", world:find("nobody") == nil)
  check.that("bodies() in creation order", #world:bodies() == 2 and world:bodies()[2] == ball)

  -- writes
  ball.velocity = {1, 0}
  ball.angular_velocity = 2
  ball.restitution = 0.75
  check.near("restitution written", ball.restitution, 0.75, 0)
  box.static = true
  check.that("box became static", box.static and box.velocity == vec2(0, 0))
  box.static = false
  box.mass = 12
  check.near("mass written; density follows", box.density, 6, 1e-12)
  box.name = "crate"
  check.that("renamed", world:find("crate") == box)

  -- impulses: Δv = J / m, Δω = (p − c) × J / I
  ball:apply_impulse({0, 4})
  check.that("impulse at the centre", ball.velocity == vec2(1, 2))
  ball:apply_impulse({0, 0.5}, ball.position + vec2(0.5, 0))
  check.near("impulse off the centre spins", ball.angular_velocity, 2 + 0.5 * 0.5 / 0.25, 1e-12)

  -- a force for one step (no duration) and the read-only fields
  local ok, message = pcall(function() box.center = {0, 0} end)
  check.that("center is read-only", not ok and message:find("body.center: is read-only", 1, true) ~= nil, message)
  ok, message = pcall(function() world.time = 3 end)
  check.that("time is read-only", not ok and message:find("world.time: is read-only", 1, true) ~= nil, message)

  -- removal
  local doomed = world:add_circle{ radius = 0.2, position = {20, 20} }
  local sp = world:add_spring{ a = doomed, anchor = {20, 25}, stiffness = 1 }
  world:remove(doomed)
  check.that("removed body", doomed.removed and sp.removed)
  ok, message = pcall(function() return doomed.position end)
  check.that("a removed body's fields are errors", not ok and message:find("was removed", 1, true) ~= nil, message)
  check.that("the next id is 4", world:add_circle{ radius = 0.1, position = {30, 30} }.id == 4)

  -- sandbox: no io, os, package, debug, coroutine, dofile, loadfile, string.dump; text-only load
  for _, name in ipairs{ "io", "os", "package", "debug", "coroutine", "dofile", "loadfile" } do
    check.that(name .. " is not available", _G[name] == nil)
  end
  check.that("string.dump is not available", string.dump == nil)
  check.that("getmetatable('') is locked", getmetatable("") == false)
  local f, err = load("\27Lua binary")
  check.that("binary chunks are refused", f == nil and err:find("binary", 1, true) ~= nil, tostring(err))
  check.that("text chunks load", load("return 1 + 1")() == 2)
  ok, message = pcall(setmetatable, {}, { __gc = function() end })
  check.that("__gc is refused", not ok and message:find("__gc", 1, true) ~= nil, message)
  check.that("collectgarbage('count') works", type(collectgarbage("count")) == "number")
end

function OnStep(world, dt)
  steps_seen = steps_seen + 1
  check.near("OnStep receives dt", dt, 0.1, 0)
end

function Check(world)
  check.near("OnStep ran once per step", steps_seen, 10, 0)
  check.near("time after 10 steps of 0.1 s", world.time, 1.0, 1e-12)
  -- semi-implicit Euler, no forces: the ball moved with its velocity
  check.near("ball x after 1 s", ball.position.x, 5 + 1, 1e-12)
end
