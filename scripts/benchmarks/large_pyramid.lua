-- Box2D v3's "large pyramid" benchmark, built as rigidlab's C++ suite builds it (`rigidlab bench
-- large_pyramid`, engine/app/bench_suite.cpp): a pyramid of 1 m boxes with a base of 100 (5050
-- boxes, density 1, friction 0.6) on a static 200 m × 2 m ground box, gravity (0, −10), sleeping
-- off, 500 steps of 1/60 s. It measures one large island: 5050 boxes in resting contact, solved
-- together every step. Check: the pyramid stands. Its 100 layers settle a little under their
-- weight (the top box 0.19 m lower after the 500 steps): the top box stays within 0.3 m of its
-- height and 0.1 m of the middle, no box moves more than 0.3 m, and none sinks into the ground.
local check = require "check"

local base, a = 100, 0.5
scene = { title = "Benchmark: large pyramid (base 100)", gravity = {0, -10}, sleeping = false, duration = 500 / 60,
          camera = { center = {0, 50}, height = 110 } }

local built = {}

function PopulateWorld(world)
  world:add_box{ width = 200, height = 2, position = {0, -1}, static = true }
  for i = 0, base - 1 do
    for j = i, base - 1 do
      local box = world:add_box{ width = 1, height = 1,
                                 position = {(i + 1.0) * a + 2.0 * (j - i) * a - a * base, (2.0 * i + 1.0) * a} }
      built[#built + 1] = { body = box, at = box.position }
    end
  end
end

function Check(world)
  local worst, lowest = 0, math.huge
  for _, b in ipairs(built) do
    local p = b.body.position
    worst = math.max(worst, (p - b.at):length())
    lowest = math.min(lowest, p.y)
  end
  local top = built[#built]
  local drop, dx = top.at.y - top.body.position.y, top.body.position.x - top.at.x
  print(string.format("after %g s: top box %.4f m lower, %.2e m aside; largest displacement %.4f m; lowest box centre %.4f m",
                      world.time, drop, dx, worst, lowest))
  check.that("5050 boxes and the ground", #world:bodies() == #built + 1 and #built == 5050)
  -- Measured after the full 500 steps: the top box 0.185 m lower and 0.040 m aside, no box more
  -- than 0.19 m from where it was built (the pyramid settles as its 100 layers press together),
  -- the lowest centre 2.8 mm into the ground. A pyramid that collapses drops its top by metres.
  check.less("top box height loss", drop, 0.3)
  check.less("top box sideways", math.abs(dx), 0.1)
  check.less("largest displacement of a box", worst, 0.3)
  check.greater("lowest box centre (0.5 m: resting on the ground)", lowest, 0.5 - 0.01)
end
