-- Box2D v3's "spinner" benchmark, built as rigidlab's C++ suite builds it (`rigidlab bench
-- spinner`, engine/app/bench_suite.cpp): 6076 small bodies (capsules, discs and squares in turn,
-- density 0.25, friction 0.1, restitution 0.1) inside a ring of radius 40 m (a closed chain of 360
-- points, friction 0.1), stirred by a 40 m paddle turning at 5 rad/s on a motor of unlimited
-- torque. Gravity (0, −10), sleeping on, 500 steps of 1/60 s. It measures a large pile kept in
-- motion by the paddle: contacts begin and end all the time. Box2D's paddle is a box rounded
-- by 0.2 m; rigidlab's polygons have no rounding, so here, as in the C++ scene, it is the box that
-- encloses the rounded one (1.2 m × 40.4 m).
--
-- One thing the Lua API cannot say: the C++ scene gives the motor an infinite max_motor_torque,
-- which add_revolute refuses (it must be finite). The scene gives it the largest finite number
-- instead, 1.7976931348623157e308 N·m: the motor's impulse is clamped to that times the step, a
-- bound it never comes near, so the paddle moves exactly as with an infinite one (the test that
-- compares this scene with the C++ one checks that the bodies' states are the same bits).
--
-- Check: the paddle turns on its pin at close to its motor's 5 rad/s, and most bodies stay inside
-- the ring (those the paddle pushes out through it are counted).
local check = require "check"

local center, radius = vec2(0, 32), 40
local unlimited = 1.7976931348623157e308  -- the largest finite double: add_revolute refuses math.huge
scene = { title = "Benchmark: spinner", gravity = {0, -10}, duration = 500 / 60, camera = { center = {0, 32}, height = 90 } }

local paddle
local stirred = {}

function PopulateWorld(world)
  local points = {}
  for i = 0, 359 do
    local t = -2.0 * math.pi * i / 360
    points[#points + 1] = {40.0 * math.cos(t), 40.0 * math.sin(t) + 32.0}
  end
  local ring = world:add_chain{ points = points, loop = true, friction = 0.1 }
  paddle = world:add_box{ width = 2.0 * (0.4 + 0.2), height = 2.0 * (20.0 + 0.2), position = {0, 12}, friction = 0 }
  world:add_revolute{ a = ring, b = paddle, anchor = {0, 12}, motor_speed = 5, max_motor_torque = unlimited }
  local x, y = -23.0, 2.0
  for i = 0, 2 * 3038 - 1 do
    local options = { position = {x, y}, density = 0.25, friction = 0.1, restitution = 0.1 }
    if i % 3 == 0 then
      options.a, options.b, options.radius = {-0.25, 0}, {0.25, 0}, 0.25
      stirred[#stirred + 1] = world:add_capsule(options)
    elseif i % 3 == 1 then
      options.radius = 0.35
      stirred[#stirred + 1] = world:add_circle(options)
    else
      options.width, options.height = 0.7, 0.7
      stirred[#stirred + 1] = world:add_box(options)
    end
    x = x + 0.5
    if x >= 23.0 then
      x, y = -23.0, y + 0.5
    end
  end
end

function Check(world)
  local outside, farthest = 0, 0
  for _, b in ipairs(stirred) do
    local d = (b.center - center):length()
    farthest = math.max(farthest, d)
    if d > radius then outside = outside + 1 end
  end
  local off_pin = (paddle.position - vec2(0, 12)):length()
  local mean_speed = world.time > 0 and paddle.angle / world.time or 5
  print(string.format("after %g s: paddle at %.4f rad/s, %.4f rad/s on average, %.3g m off its pin; %d bodies outside the ring (the farthest %.1f m from its centre)",
                      world.time, paddle.angular_velocity, mean_speed, off_pin, outside, farthest))
  check.that("the ring, the paddle and 6076 bodies", #world:bodies() == 6078 and #stirred == 6076)
  -- Measured over the 500 steps: 4.72 rad/s on average. The paddle reaches 40.2 m from the ring's
  -- centre, 0.2 m past the ring (in Box2D's scene too): each time its lower end passes the bottom
  -- of the ring it is held back for a few steps, and bodies caught there are pushed out through
  -- the ring, 82 in the first 25 steps and 376 (6 %) by the end, thrown up to 1.4 km away.
  check.near("the paddle's average speed: the motor's 5 rad/s, less its stalls at the bottom", mean_speed, 4.75, 0.25)
  check.less("the paddle stays on its pin", off_pin, 0.01)
  check.less("bodies pushed out through the ring", outside, 0.1 * #stirred)
end
