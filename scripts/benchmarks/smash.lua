-- Box2D v3's "smash" benchmark, built as rigidlab's C++ suite builds it (`rigidlab bench smash`,
-- engine/app/bench_suite.cpp): a heavy 8 m box (density 8, 512 kg) at 40 m/s into a wall of
-- 120 × 80 boxes of 0.4 m (9600, density 1) created asleep, without gravity, sleeping on, 300 steps
-- of 1/60 s. It measures waking: the wall costs nothing until the box reaches it after about 1.15 s,
-- then the impact wakes it and spreads through it as a growing island of contacts, in which the
-- boxes scatter.
--
-- Check: nothing but the box moves and the wall sleeps until the box reaches it, the box keeps its
-- 40 m/s exactly until then; afterwards it has slowed down, and with no gravity and no ground the
-- bodies' total momentum stays the box's 512 kg × 40 m/s, along x.
local check = require "check"

local size, columns, rows = 0.4, 120, 80
scene = { title = "Benchmark: smash", gravity = {0, 0}, duration = 300 / 60, camera = { center = {20, 0}, height = 60 } }

local box
local wall = {}
local impact_time = (30.0 - 0.5 * size - (-20 + 4)) / 40  -- the box's front face reaches the wall

function PopulateWorld(world)
  box = world:add_box{ width = 8, height = 8, position = {-20, 0}, velocity = {40, 0}, density = 8 }
  for i = 0, columns - 1 do
    for j = 0, rows - 1 do
      wall[#wall + 1] = world:add_box{ width = size, height = size, position = {i * size + 30.0, (j - rows / 2) * size},
                                       awake = false }
    end
  end
end

function Check(world)
  local px, py, awake = box.mass * box.velocity.x, box.mass * box.velocity.y, 0
  for _, b in ipairs(wall) do
    px, py = px + b.mass * b.velocity.x, py + b.mass * b.velocity.y
    if b.awake then awake = awake + 1 end
  end
  local p0 = box.mass * 40
  print(string.format("after %g s: box at %.2f m/s, %d of %d wall boxes awake; momentum off by (%.3g, %.3g) kg m/s of %g",
                      world.time, box.velocity.x, awake, #wall, px - p0, py, p0))
  check.that("the box and 9600 wall boxes", #world:bodies() == 9601 and #wall == 9600)
  check.near("the box's mass", box.mass, 512, 1e-9)
  if world.time < impact_time then
    check.that("before the impact the box keeps 40 m/s exactly", box.velocity.x == 40 and box.velocity.y == 0)
    check.that("and the wall sleeps", awake == 0)
  else
    check.less("the box slowed down", box.velocity.x, 25)  -- measured 17.1 m/s after the 300 steps
    check.greater("the impact woke the wall", awake, 0)
  end
  -- Measured after the 300 steps: off by 1.9e-10 kg m/s along x and 5.8e-13 along y (round-off:
  -- contact impulses are equal and opposite).
  check.near("momentum along x", px, p0, 1e-9 * p0)
  check.near("momentum along y", py, 0, 1e-9 * p0)
end
