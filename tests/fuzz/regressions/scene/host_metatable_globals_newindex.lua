-- getmetatable(_G) gave the host's recorder of the `scene` line; its __newindex with a number as
-- the table crashed in lua_rawset (SIGSEGV).
local mt = getmetatable(_G)
if type(mt) == "table" and mt.__newindex then mt.__newindex(1, "scene", 2) end
function PopulateWorld(world) end
