-- Bodies and their names are host memory: they count against memory_limit, so a scene cannot
-- make the host allocate without bound by adding bodies.
-- exit: 1
-- expect: string_names_counted.lua:9: add_box: not enough memory (the scene's limit is 8 MiB); bodies, shapes, joints and their names count against it
scene = { memory_limit = 8 }
local name = string.rep("b", 256)
function PopulateWorld(world)
  for i = 1, 1e6 do
    world:add_box{ width = 1, height = 1, position = {2 * i, 0}, name = name }
  end
end
