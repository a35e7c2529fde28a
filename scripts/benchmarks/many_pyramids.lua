-- Box2D v3's "many pyramids" benchmark, built as rigidlab's C++ suite builds it (`rigidlab bench
-- many_pyramids`, engine/app/bench_suite.cpp): 20 rows of 20 pyramids of 1 m boxes with a base of
-- 10 (400 pyramids, 22 000 boxes, density 1, friction 0.6), each row standing on its own ground
-- segment (one static body holding the 20 segments), gravity (0, −10), sleeping off, 200 steps of
-- 1/60 s. It measures many small islands at once: 400 separate piles of 55 boxes, each an island
-- of its own. Check: every pyramid stands: each one's top box stays within 1 cm of where it was
-- built, no box moves more than 1 cm, and none sinks into its segment.
local check = require "check"

local base, rows, columns, extent = 10, 20, 20, 0.5
local ground_dy, ground_width = 2.0 * extent * (base + 1.0), 2.0 * extent * columns * (base + 1.0)
scene = { title = "Benchmark: many pyramids (400 of base 10)", gravity = {0, -10}, sleeping = false,
          duration = 200 / 60, camera = { center = {0, 0.5 * (rows - 1) * ground_dy + 5}, height = rows * ground_dy + 10 } }

local boxes = {}  -- in the order they were built: pyramid by pyramid, row by row from the base

-- Where the C++ scene puts box (i, j) of the pyramid in row r, column c (the same arithmetic, so
-- the same bits).
local function built_at(r, c, i, j)
  local base_width = 2.0 * extent * base
  local center_x = -0.5 * ground_width + c * (base_width + 2.0 * extent) + 2.0 * extent
  return vec2((i + 1.0) * extent + 2.0 * (j - i) * extent + center_x - 0.5, (2.0 * i + 1.0) * extent + r * ground_dy)
end

-- Calls f(box index, r, c, i, j) for every box in the order they are built.
local function each_box(f)
  local k = 0
  for r = 0, rows - 1 do
    for c = 0, columns - 1 do
      for i = 0, base - 1 do
        for j = i, base - 1 do
          k = k + 1
          f(k, r, c, i, j)
        end
      end
    end
  end
end

function PopulateWorld(world)
  local ground = world:add_body{ type = "static" }
  for i = 0, rows - 1 do
    ground:add_shape{ shape = "segment", a = {-0.5 * ground_width, i * ground_dy}, b = {0.5 * ground_width, i * ground_dy} }
  end
  each_box(function(k, r, c, i, j)
    boxes[k] = world:add_box{ width = 2 * extent, height = 2 * extent, position = built_at(r, c, i, j) }
  end)
end

function Check(world)
  local worst, sunk, drop, aside = 0, -math.huge, 0, 0
  each_box(function(k, r, c, i, j)
    local at, p = built_at(r, c, i, j), boxes[k].position
    worst = math.max(worst, (p - at):length())
    sunk = math.max(sunk, r * ground_dy + extent - p.y)  -- > 0: a box centre lower than half a box above its segment
    if i == base - 1 then  -- the top box
      drop, aside = math.max(drop, at.y - p.y), math.max(aside, math.abs(p.x - at.x))
    end
  end)
  print(string.format("after %g s: top boxes at most %.4f m lower and %.2e m aside; largest displacement %.4f m; deepest box %.4f m into its segment",
                      world.time, drop, aside, worst, sunk))
  check.that("22 000 boxes and the ground", #world:bodies() == #boxes + 1 and #boxes == 22000)
  -- Measured after the 200 steps: top boxes 2.0 mm lower and 0.07 mm aside at most, no box more
  -- than 2.0 mm from where it was built, none more than 0.2 mm into its segment.
  check.less("a top box's height loss", drop, 0.01)
  check.less("a top box sideways", aside, 0.001)
  check.less("largest displacement of a box", worst, 0.01)
  check.less("deepest box into its segment", sunk, 0.005)
end
