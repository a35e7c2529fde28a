-- Box2D v3's "junkyard" benchmark, built as rigidlab's C++ suite builds it (`rigidlab bench
-- junkyard`, engine/app/bench_suite.cpp): 200 columns × 40 rows of pentagons (8000, radius
-- 0.25 m, density 1, friction 0.6) fall from 15 to 54 m into a 160 m container of small static
-- boxes (a floor of 161, two walls of 50), where a kinematic pusher, a 4 × 8 m box standing on
-- the floor, sweeps them: before step k its velocity is set (set_target, v3's
-- b2Body_SetTargetTransform) to take it to x = 60 sin(0.2 k dt) in one step. Gravity (0, −10),
-- sleeping on, 800 steps of 1/60 s. It measures a large pile shoved about by a kinematic body.
--
-- Check: the pusher follows its path exactly, every pentagon falls freely until the lowest row
-- lands, and every pentagon stays inside the container.
local check = require "check"

local columns, rows, radius = 200, 40, 0.25
local dt = 1 / 60
scene = { title = "Benchmark: junkyard", gravity = {0, -10}, duration = 800 / 60, camera = { center = {0, 25}, height = 60 } }

local pusher
local pentagons = {}
local start = {}

local function add_container(ground, half, wall)
  for i = 0, 2 * half do ground:add_shape{ shape = "box", width = 1.1, height = 1.0, offset = {i - half, 0.0} } end
  for _, side in ipairs{ -1, 1 } do
    for i = 0, wall - 1 do ground:add_shape{ shape = "box", width = 1.0, height = 1.1, offset = {side * half, i + 1.0} } end
  end
end

local function push(step)
  pusher:set_target{ position = {60.0 * math.sin(0.2 * dt * step), 0.0}, angle = 0.0, time = dt }
end

function PopulateWorld(world)
  add_container(world:add_body{ type = "static" }, 80, 50)
  -- v3's pentagon: the points of the circle of radius 0.25 at the angles k φ, φ = π(√5 − 1), in
  -- angular order (k = 0, 2, 4, 1, 3).
  local phi = math.pi * (math.sqrt(5.0) - 1.0)
  local pentagon = {}
  for _, k in ipairs{ 0, 2, 4, 1, 3 } do pentagon[#pentagon + 1] = { radius * math.cos(phi * k), radius * math.sin(phi * k) } end
  local side = -0.1  -- every other body (counted across the columns) 0.1 m left, the others right
  for i = 0, columns - 1 do
    for j = 0, rows - 1 do
      local body = world:add_body{ position = {1.5 * (2.0 * i - columns) * radius + side, 4.0 * j * radius + 15.0} }
      body:add_shape{ shape = "polygon", vertices = pentagon }
      pentagons[#pentagons + 1] = body
      start[#start + 1] = body.position
      side = -side
    end
  end
  pusher = world:add_body{ type = "kinematic" }
  pusher:add_shape{ shape = "box", width = 4.0, height = 8.0, offset = {0.0, 4.0} }
  push(0)
end

function OnStep(world)
  push(world.step_count)  -- before the next step, as the C++ scene's before_step
end

function Check(world)
  local t, free_error, outside = world.time, 0, 0
  for i, b in ipairs(pentagons) do
    free_error = math.max(free_error, (b.position - (start[i] - vec2(0, 5 * t * t))):length())
    if b.position.y < 0 or math.abs(b.position.x) > 80 then outside = outside + 1 end
  end
  -- After k steps the pusher stands where step k − 1 was told to take it.
  local k = world.step_count
  local expected = k > 0 and 60.0 * math.sin(0.2 * dt * (k - 1)) or 0.0
  print(string.format("after %g s: pusher at x = %.6f m (its path: %.6f), largest distance from free fall %.3g m, %d pentagons outside",
                      t, pusher.position.x, expected, free_error, outside))
  check.that("the ground, 8000 pentagons and the pusher", #world:bodies() == 8002 and #pentagons == 8000)
  check.near("the pusher follows its path", pusher.position.x, expected, 1e-9)
  check.near("on the floor", pusher.position.y, 0.0, 1e-12)
  -- The lowest row reaches the floor's top (0.5 m) after √(2 · 14.25 / 10) = 1.69 s.
  if t < 1.6 then check.less("every pentagon falls freely", free_error, 1e-9) end
  check.that("every pentagon inside the container", outside == 0)
end
