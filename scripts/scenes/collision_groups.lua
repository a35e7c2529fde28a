-- Collision filtering as in Box2D: categories and masks, and groups. Red and blue bodies pass
-- through each other (each one's mask leaves out the other's category); green collides with both.
-- Two crates of one negative group pass through each other although their masks would collide.
-- Everything lands on the ground (category 1, collides with all). At the end the geometry says who
-- ended inside whom: each pair either overlaps deeply or touches at most by the contact slop.
local check = require "check"

scene = { title = "Collision groups", dt = 1/60, duration = 2, camera = { center = {0, 2}, height = 6 } }

local RED, BLUE, GREEN = 2, 4, 8
local b = {}

function PopulateWorld(world)
  world:add_box{ width = 20, height = 1, position = {0, -0.5}, static = true }
  -- A blue slab on the ground; a red ball and a green block dropped on it, side by side.
  b.blue = world:add_box{ width = 3, height = 1, position = {0, 0.5}, category = BLUE, mask = ~RED }
  b.red = world:add_circle{ radius = 0.3, position = {-0.8, 3}, category = RED, mask = ~BLUE }
  b.green = world:add_box{ width = 0.8, height = 0.6, position = {0.8, 3}, category = GREEN }
  -- A red crate dropped on the green block: red collides with green.
  b.red_on_green = world:add_box{ width = 0.4, height = 0.4, position = {0.8, 4.5}, category = RED, mask = ~BLUE }
  -- Two crates of group -1: one dropped onto the other, which it falls through.
  b.low = world:add_box{ width = 1, height = 1, position = {5, 0.5}, group = -1 }
  b.high = world:add_box{ width = 1, height = 1, position = {5, 2.5}, group = -1 }
end

-- How deep two axis-aligned bodies overlap vertically, m (< 0: a gap), from their centres and
-- half heights (every body here stays upright: check.near of the angles below).
local function overlap(p, hp, q, hq) return hp + hq - math.abs(p.position.y - q.position.y) end

function Check(world)
  for name, body in pairs(b) do check.near(name .. " stays upright", body.angle, 0, 1e-6) end
  local red_blue = overlap(b.red, 0.3, b.blue, 0.5)
  local green_blue = overlap(b.green, 0.3, b.blue, 0.5)
  local red_green = overlap(b.red_on_green, 0.2, b.green, 0.3)
  local groups = overlap(b.low, 0.5, b.high, 0.5)
  print(string.format("overlaps: red-blue %.3f, green-blue %.4f, red crate-green %.4f, group -1 crates %.3f m",
                      red_blue, green_blue, red_green, groups))
  -- Red fell through the slab to the ground: its centre 0.3 m up, inside the slab.
  check.near("red passed through blue onto the ground", b.red.position.y, 0.3, 0.01)
  check.greater("red and blue overlap", red_blue, 0.5)
  -- The green block rests on the slab, the red crate on it: contacts, overlapping by at most the slop.
  check.near("green rests on blue", b.green.position.y, 1.3, 0.01)
  check.less("green and blue do not overlap (beyond the slop)", green_blue, 0.01)
  check.near("the red crate rests on green", b.red_on_green.position.y, 1.6 + 0.2, 0.02)
  check.less("red and green do not overlap", red_green, 0.01)
  check.greater("the group -1 crates sit inside each other", groups, 0.9)
end
