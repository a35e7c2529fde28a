-- A title of 30 000 characters aborted the sandbox's overlay (Dear ImGui's vertex limit). Titles
-- are at most 256 bytes.
-- exit: 1
-- expect: string_title.lua:5: scene: title must be at most 256 bytes long, got 30000
scene = { title = string.rep("T", 30000) }
function PopulateWorld(world) end
