-- Host metatables: _G's metatable while the main chunk runs is the host's recorder of the `scene`
-- line; its __newindex crashed (SIGSEGV in lua_rawset) when called with a number as the table.
-- getmetatable(_G) must not give it out, and a scene may still set a metatable of its own on _G.
-- expect: getmetatable(_G): false
-- expect: strict mode works
local mt = getmetatable(_G)
print("getmetatable(_G): " .. tostring(mt))
assert(mt == false)
assert(not pcall(setmetatable, getmetatable(_G), {}))
-- A strict-mode metatable of the scene's own replaces the host's (the recorder steps aside).
setmetatable(_G, { __newindex = function(t, k, v) rawset(t, k, v) end, __index = function(_, k) error("undefined global " .. k, 2) end })
assert(not pcall(function() return undefined_thing end))
print("strict mode works")
setmetatable(_G, nil)
function PopulateWorld(world) end
