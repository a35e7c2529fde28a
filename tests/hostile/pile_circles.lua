-- Memory outside the Lua cap: 3000 circles created at one point made 4.5 million candidate pairs
-- and passed 2 GB in 2.4 s (one step took 11 s and 3.2 GB). The broad phase stops at its cap and
-- the step fails naming the crowd; the world is left as it was.
-- exit: 1
-- expect: pile_circles.lua: step: too many bodies on top of each other at step 1 (t = 0 s): 3000 bodies overlap around
-- expect: more than the 100000 candidate contact pairs a step may have (min(1000000, max(100000, 32 per body)) for 3000 bodies)
function PopulateWorld(world)
  for i = 1, 3000 do world:add_circle{ radius = 0.5 } end
end
