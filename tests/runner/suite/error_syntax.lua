-- Errors: a syntax error (the scene never loads).
function PopulateWorld(world)
  world:add_circle{ radius = 1 
end

function Check(world) end
