-- Finalizers: a replaced __gc used to install a Lua finalizer that ran at close against a destroyed
-- world (use-after-free in World::createBody). Every route to a finalizer is tried; none may run.
-- reject: FINALIZER RAN
-- expect: no route to a finalizer
local w
local function finalizer() print("FINALIZER RAN"); w:add_circle{ radius = 1 } end
assert(not pcall(setmetatable, {}, { __gc = finalizer }))                 -- refused outright
kept_too = setmetatable({}, setmetatable({}, { __index = { __gc = finalizer } }))  -- inherited: no finalizer
local mt = {}
local kept = setmetatable({}, mt)
mt.__gc = finalizer                                                        -- added later: inert
function PopulateWorld(world)
  w = world
  local b = world:add_circle{ radius = 1 }
  for _, handle in ipairs{ world, b } do
    local hm = getmetatable(handle)
    if type(hm) == "table" then hm.__gc = finalizer end                    -- unreachable: false
  end
  print("no route to a finalizer")
end
