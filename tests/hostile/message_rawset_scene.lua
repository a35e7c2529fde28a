-- A `scene` table set with rawset lost the line of its bad field: it gets the line of the rawset.
-- exit: 1
-- expect: message_rawset_scene.lua:5: scene: dt must be > 0, got 0
local settings = { title = "rawset", dt = 0 }
rawset(_G, "scene",
       settings)
function PopulateWorld(world) end
