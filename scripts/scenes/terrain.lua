-- A box slides at 8 m/s, without friction, over a flat ground made of one chain of 60 segments. A
-- chain's segments know their neighbours (ghost vertices), so the box's corners do not catch on
-- the seams between them: its vertical speed stays near 0 (measured 3e-14 m/s) and it keeps its
-- 8 m/s. Ground made of 60 flush static boxes of the same length instead trips the same box
-- (measured: |vy| up to 2.18 m/s at a seam; it tumbles and stops 6 m on).
local check = require "check"

scene = { title = "Terrain: a chain of 60 segments", dt = 1/60, duration = 3.5, camera = { center = {14, 1}, height = 6 } }

local segments, segment_length, speed = 60, 0.5, 8.0
local box, worst_vy, worst_angle, settled_at = nil, 0, 0, 0.25

function PopulateWorld(world)
  -- Listed right to left: the surface faces up (a chain is one-sided).
  local points = {}
  for i = segments, 0, -1 do points[#points + 1] = {i * segment_length - 1, 0} end
  world:add_chain{ points = points, friction = 0 }
  -- Resting on the ground from the start (its half height above it), already sliding.
  box = world:add_box{ width = 0.5, height = 0.5, position = {0, 0.25}, velocity = {speed, 0}, friction = 0 }
end

function OnStep(world, dt)
  if world.time > settled_at and box.position.x < (segments - 1) * segment_length - 1 then
    worst_vy = math.max(worst_vy, math.abs(box.velocity.y))
    worst_angle = math.max(worst_angle, math.abs(box.angle))
  end
end

function Check(world)
  print(string.format("box crossed to x = %.2f; worst |vy| %.3g m/s, worst |angle| %.3g rad, vx %.6f m/s",
                      box.position.x, worst_vy, worst_angle, box.velocity.x))
  check.greater("the box crossed most of the 60 segments", box.position.x, 0.8 * segments * segment_length)
  check.less("|vy| over the seams (ghost vertices)", worst_vy, 0.05)
  check.less("the box does not tip at a seam", worst_angle, 0.01)
  check.near("no friction: it keeps its speed", box.velocity.x, speed, 1e-6)
end
