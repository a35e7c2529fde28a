-- 3 MiB alive, then memory_limit = 1: a memory error while the host read the scene table aborted
-- (terminate called after throwing an instance of 'sol::error').
keep = {}
for i = 1, 3 * 1024 do keep[i] = string.rep("x", 1000) .. i end
scene = { memory_limit = 1, title = "x", gravity = {0, -1} }
function PopulateWorld(world) end
