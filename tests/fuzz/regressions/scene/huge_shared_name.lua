-- Every body copying a shared 32 MiB name into C++ passed 2 GB.
local name = string.rep("n", 32 * 1024 * 1024)
function PopulateWorld(world)
  for i = 1, 100 do world:add_circle{ radius = 0.1, position = {i, 0}, name = name } end
end
