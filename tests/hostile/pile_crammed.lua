-- Time of the broad phase without pairs: one large dynamic box makes the grid's cells huge, and
-- 20 000 small static discs that touch nothing fill one cell: 2e8 box tests per step. The step
-- stops at its test limit instead of taking seconds.
-- exit: 1
-- expect: step: too many bodies crammed into one place at step 1 (t = 0 s): 20000 bodies share a grid cell around
function PopulateWorld(world)
  world:add_box{ width = 400, height = 400, position = {-1000, 0} }
  for i = 0, 19999 do
    world:add_circle{ radius = 0.004, position = {(i % 200) * 0.01, (i // 200) * 0.01}, static = true }
  end
end
