-- Strings copied out of Lua: every body copying a shared 32 MiB name into C++ passed 2 GB in 2 s.
-- Names are at most 256 bytes, refused before anything is copied.
-- exit: 1
-- expect: string_name.lua:8: add_circle: name must be at most 256 bytes long, got 33554432
local name = string.rep("n", 32 * 1024 * 1024)
function PopulateWorld(world)
  for i = 1, 100 do
    world:add_circle{ radius = 0.1, position = {i, 0}, name = name }
  end
end
