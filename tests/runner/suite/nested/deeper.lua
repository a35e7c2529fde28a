-- Passes, one folder down: discovery is recursive.
scene = { dt = 0.05, duration = 0.5 }

function PopulateWorld(world)
  world:add_circle{ radius = 0.5 }
end

Check = function(world) end
