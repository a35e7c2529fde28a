-- A wall of bricks welded to their neighbours (break_force 600 N each), standing on ice, hit on its
-- left side by a heavy ball. A weld carries the force that accelerates the bricks beyond it, so the
-- welds near the blow break (removed at the end of the step; their handles say broken) and those far
-- from it, which push only the last few bricks, hold. The floor has no friction so that it does not
-- drag the bottom row and shear the rows apart along the whole wall. Measured: 18 of the 82 welds
-- break, none in the two columns farthest from the ball (the breaks reach the seam between columns
-- 6 and 7). The wall is built asleep (awake = false), as a level's wall
-- waiting to be hit: it costs nothing until the ball wakes it.
local check = require "check"

scene = { title = "Breakable wall", dt = 1/60, duration = 1.2, camera = { center = {2, 1}, height = 5 } }

local cols, rows, w, h = 8, 6, 0.5, 0.25
local wall_x = 1.0
local far_x = wall_x + (cols - 2) * w  -- the last two columns' welds lie beyond it
local welds = {}  -- { joint =, x = } with x the weld's anchor x
local bricks = {}
local slept_until_hit = true

function PopulateWorld(world)
  world:add_box{ width = 30, height = 1, position = {0, -0.5}, static = true, friction = 0 }
  for row = 1, rows do
    bricks[row] = {}
    for col = 1, cols do
      local at = vec2(wall_x + (col - 0.5) * w, (row - 0.5) * h)
      bricks[row][col] = world:add_box{ width = w, height = h, position = at, mass = 2, friction = 0,
                                         awake = false }
      -- Glued to the brick on its left and to the one below.
      local function glue(other, anchor)
        welds[#welds + 1] = { joint = world:add_weld{ a = bricks[row][col], b = other, anchor = anchor, break_force = 600 },
                              x = anchor.x }
      end
      if col > 1 then glue(bricks[row][col - 1], at - vec2(w / 2, 0)) end
      if row > 1 then glue(bricks[row - 1][col], at - vec2(0, h / 2)) end
    end
  end
  world:add_circle{ radius = 0.3, position = {-1.5, 0.8}, velocity = {12, 0}, mass = 10, name = "ball" }
end

function OnStep(world, dt)
  -- The ball reaches the wall after (1 − 0.3 + 1.5) / 12 = 0.18 s.
  if world.time < 0.15 then
    for _, row in ipairs(bricks) do
      for _, brick in ipairs(row) do slept_until_hit = slept_until_hit and not brick.awake end
    end
  end
end

function Check(world)
  check.that("the wall slept until the ball came", slept_until_hit)
  local broken, far, far_broken = 0, 0, 0
  for _, weld in ipairs(welds) do
    if weld.joint.broken then broken = broken + 1 end
    if weld.x > far_x + 0.1 then
      far = far + 1
      if weld.joint.broken then far_broken = far_broken + 1 end
    end
  end
  print(string.format("%d of %d welds broke (%d left in the world); %d of the %d in the last two columns", broken, #welds,
                      #world:joints(), far_broken, far))
  check.greater("the ball broke welds", broken, 0)
  check.that("every broken weld was removed, the others kept", #world:joints() == #welds - broken)
  check.less("but not most of them", broken, #welds / 2)
  check.that("the last two columns keep their welds", far_broken == 0, far_broken .. " broke")
end
