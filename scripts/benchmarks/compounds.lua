-- Box2D v3's "compounds" benchmark, built as rigidlab's C++ suite builds it (`rigidlab bench
-- compounds`, engine/app/bench_suite.cpp): 20 columns × 150 rows of bodies of two overlapping
-- triangles each (3000 bodies, 6000 shapes, density 1, friction 0.5; v3's samples' barrel of
-- compound shapes) fall from 5.6 to 341 m into an 80 m container of small static boxes (a floor of
-- 81, two walls of 100, friction 0.6) over a 1600 m segment 80 m below that catches what falls out.
-- Gravity (0, −10), sleeping on, 500 steps of 1/60 s. It measures compound bodies (two polygons
-- each, so two contacts where one would do) landing and piling up while the rows above still fall.
--
-- Check: until the lowest row lands every body falls freely, exactly; afterwards every body stays
-- inside the container.
local check = require "check"

local columns, rows = 20, 150
scene = { title = "Benchmark: compounds", gravity = {0, -10}, duration = 500 / 60, camera = { center = {0, 45}, height = 110 } }

local bodies = {}
local start = {}
local left = { {-1.0, 0.0}, {0.5, 1.0}, {0.0, 2.0} }
local right = { {1.0, 0.0}, {-0.5, 1.0}, {0.0, 2.0} }

-- The container that compounds and junkyard share: a floor of 1.1 × 1 m boxes 1 m apart along
-- y = 0 from x = −half to half, and at x = ±half a wall of `wall` 1 × 1.1 m boxes from y = 1.
local function add_container(ground, half, wall)
  for i = 0, 2 * half do ground:add_shape{ shape = "box", width = 1.1, height = 1.0, offset = {i - half, 0.0} } end
  for _, side in ipairs{ -1, 1 } do
    for i = 0, wall - 1 do ground:add_shape{ shape = "box", width = 1.0, height = 1.1, offset = {side * half, i + 1.0} } end
  end
end

function PopulateWorld(world)
  local ground = world:add_body{ type = "static" }
  add_container(ground, 40, 100)
  ground:add_shape{ shape = "segment", a = {-800.0, -80.0}, b = {800.0, -80.0} }
  -- v3's sample's layout: columns 2 m apart centred on x = 0, rows 2.25 m apart from y = 5.575,
  -- every other body (counted across the columns) 0.25 m to the right, the others to the left.
  local shift, extra_y, y_start = 2.0, 0.25, 5.0
  local center_x, center_y = shift * columns / 2.0 - 1.0, 1.15 / 2.0
  local side = 0.25
  for i = 0, columns - 1 do
    for j = 0, rows - 1 do
      local body = world:add_body{ position = {i * shift - center_x + side, j * (shift + extra_y) + center_y + y_start} }
      body:add_shape{ shape = "polygon", vertices = left, friction = 0.5 }
      body:add_shape{ shape = "polygon", vertices = right, friction = 0.5 }
      bodies[#bodies + 1] = body
      start[#start + 1] = body.position
      side = -side
    end
  end
end

function Check(world)
  local t, free_error, outside = world.time, 0, 0
  for i, b in ipairs(bodies) do
    free_error = math.max(free_error, (b.position - (start[i] - vec2(0, 5 * t * t))):length())
    if b.position.y < 0 or math.abs(b.position.x) > 40 then outside = outside + 1 end
  end
  print(string.format("after %g s: %d bodies, largest distance from free fall %.3g m, %d outside the container",
                      t, #bodies, free_error, outside))
  check.that("the ground and 3000 bodies of two triangles",
             #world:bodies() == 3001 and #bodies == 3000 and #bodies[1].shapes == 2)
  -- The lowest row's bottom corners reach the floor's top (0.5 m) after √(2 · 5.075 / 10) = 1.007 s.
  if t < 1.0 then check.less("every body falls freely", free_error, 1e-9) end
  -- Measured after the 500 steps: none out (the last rows are still landing).
  check.that("every body inside the container", outside == 0)
end
