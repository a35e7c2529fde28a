-- Box2D v3's "tumbler" benchmark, built as rigidlab's C++ suite builds it (`rigidlab bench
-- tumbler`, engine/app/bench_suite.cpp): a 20 m square drum of four 1 m thick walls (density 50),
-- pinned at its centre to a static body and turned at 25°/s by a motor (at most 10⁸ N·m), tumbling
-- 45 × 45 boxes of 0.25 m (2025, density 1, friction 0.6). Gravity (0, −10), sleeping on, 750 steps
-- of 1/60 s. It measures a pile that never settles: the boxes slide and fall inside the turning
-- drum, so contacts keep beginning and ending and nothing sleeps.
--
-- Check: the drum turns at its motor's speed about its pin, and every box stays inside the drum.
local check = require "check"

local motor_speed = math.pi / 180.0 * 25.0
local grid, half_inside = 45, 9.5
scene = { title = "Benchmark: tumbler", gravity = {0, -10}, duration = 750 / 60, camera = { center = {0, 10}, height = 32 } }

local drum
local boxes = {}

function PopulateWorld(world)
  local ground = world:add_body{ type = "static" }
  drum = world:add_body{ position = {0, 10} }
  drum:add_shape{ shape = "box", width = 1, height = 20, offset = {10, 0}, density = 50 }
  drum:add_shape{ shape = "box", width = 1, height = 20, offset = {-10, 0}, density = 50 }
  drum:add_shape{ shape = "box", width = 20, height = 1, offset = {0, 10}, density = 50 }
  drum:add_shape{ shape = "box", width = 20, height = 1, offset = {0, -10}, density = 50 }
  world:add_revolute{ a = ground, b = drum, anchor = {0, 10}, motor_speed = motor_speed, max_motor_torque = 1e8 }
  local y = -0.2 * grid + 10.0
  for _ = 1, grid do
    local x = -0.2 * grid
    for _ = 1, grid do
      boxes[#boxes + 1] = world:add_box{ width = 0.25, height = 0.25, position = {x, y} }
      x = x + 0.4
    end
    y = y + 0.4
  end
end

function Check(world)
  local outside = -math.huge  -- how far a box's centre is past the inside of the walls, in the drum's frame
  local c, s = math.cos(drum.angle), math.sin(drum.angle)
  for _, b in ipairs(boxes) do
    local d = b.position - drum.position
    local x, y = c * d.x + s * d.y, -s * d.x + c * d.y
    outside = math.max(outside, math.abs(x) - half_inside, math.abs(y) - half_inside)
  end
  local off_pin = (drum.position - vec2(0, 10)):length()
  print(string.format("after %g s: drum at %.6f rad/s (motor %.6f), angle %.4f rad (%.4f at the motor's speed), %.3g m off its pin; box centres at least %.4f m inside the walls",
                      world.time, drum.angular_velocity, motor_speed, drum.angle, motor_speed * world.time, off_pin, -outside))
  check.that("the ground, the drum and 2025 boxes", #world:bodies() == 2027 and #boxes == 2025)
  check.near("the drum turns at the motor's speed", drum.angular_velocity, motor_speed, 1e-3 * motor_speed)
  check.near("its angle", drum.angle, motor_speed * world.time, 0.01)
  check.less("the drum stays on its pin", off_pin, 1e-3)
  -- Measured: a box centre 0.116 m from the inside of a wall at least (a box lying flat on a wall
  -- is 0.125 m from it; a box outside the drum would read above 0).
  check.less("every box inside the drum", outside, -0.1)
end
