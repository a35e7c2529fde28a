-- An explosion (world:explode) among boxes in zero gravity: which bodies it pushes and by how much.
-- The core's rule (Box2D's b2World_Explode): a shape whose closest point lies at distance d from
-- the centre gets an impulse away from the centre of
--   J = impulse · (the width it shows to the centre) · s,   s = 1 for d ≤ radius,
--   s = 1 − (d − radius) / falloff up to radius + falloff, 0 beyond,
-- at that closest point. The boxes below face the centre squarely (width 1 m, closest point on
-- the line through their centres), so each one's speed is J / m along the line, without spin.
local check = require "check"

scene = { title = "Explosion", dt = 1 / 60, duration = 0.5, gravity = {0, 0}, camera = { center = {0, 0}, height = 20 } }

local radius, falloff, impulse = 2, 4, 3
-- Distance of each box's near face from the centre, and the direction it lies in.
local layout = {
  { d = 1.0, dir = vec2(1, 0) }, { d = 2.0, dir = vec2(0, 1) }, { d = 3.0, dir = vec2(-1, 0) },
  { d = 4.5, dir = vec2(0, -1) }, { d = 5.5, dir = vec2(1, 0) }, { d = 7.0, dir = vec2(0, 1) },
}
local boxes, start, pushed = {}, {}, nil
local wall

function PopulateWorld(world)
  for i, b in ipairs(layout) do
    boxes[i] = world:add_box{ name = "box " .. i, width = 1, height = 1, position = b.dir * (b.d + 0.5) }
    start[i] = boxes[i].position
  end
  -- A static wall inside the radius: explosions push only dynamic bodies.
  wall = world:add_box{ name = "wall", width = 0.5, height = 0.5, position = {1.2, 1.2}, static = true }
  pushed = world:explode{ position = {0, 0}, radius = radius, falloff = falloff, impulse = impulse }
end

local function scale(d)
  if d <= radius then return 1 end
  return math.max(0, 1 - (d - radius) / falloff)
end

function Check(world)
  local moved = {}
  for _, b in ipairs(pushed) do moved[b.name] = true end
  check.that("the wall is not pushed", not moved.wall)
  local last_speed = math.huge
  for i, b in ipairs(boxes) do
    local L = layout[i]
    local expected = impulse * 1 * scale(L.d) / b.mass
    local v = b.velocity
    check.that(b.name .. " pushed iff within radius + falloff", (moved[b.name] == true) == (L.d < radius + falloff))
    check.near(b.name .. " speed", v:length(), expected, 1e-9)
    check.near(b.name .. " along the line from the centre", v:dot(L.dir), expected, 1e-9)
    check.near(b.name .. " no spin", b.angular_velocity, 0, 1e-12)
    check.that(b.name .. " not faster than a nearer box", v:length() <= last_speed + 1e-12)
    last_speed = v:length()
    -- After the run it has moved by v t (nothing else acts).
    check.near(b.name .. " travelled", (b.position - start[i]):length(), expected * world.time, 1e-9)
  end
  check.near("the two boxes within the radius get the full impulse", boxes[1].velocity:length(),
             boxes[2].velocity:length(), 1e-12)
  check.less("the farthest box pushed is slower", boxes[5].velocity:length(), boxes[3].velocity:length())
end
