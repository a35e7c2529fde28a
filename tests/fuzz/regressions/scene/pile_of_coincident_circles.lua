-- 3000 circles at one point: 4.5 million pairs, 3.2 GB in one step. Now the step fails at the cap.
function PopulateWorld(world)
  for i = 1, 3000 do world:add_circle{ radius = 0.5 } end
end
