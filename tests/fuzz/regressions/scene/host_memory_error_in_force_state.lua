-- A Lua force that empties its state table and sets a failing __newindex on it, under memory
-- pressure: the host's refill must stay raw and protected.
scene = { memory_limit = 2 }
local keep = {}
function PopulateWorld(world)
  local b = world:add_circle{ radius = 1 }
  world:add_force{ body = b, evaluate = function(s)
    for k in pairs(s) do s[k] = nil end
    setmetatable(s, { __newindex = function() error("x") end })
    for i = 1, 1e5 do keep[#keep + 1] = {i} end
    return 0, 0
  end }
end
