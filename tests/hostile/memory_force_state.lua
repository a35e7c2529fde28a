-- The state tables the host refills for a Lua force: the force empties its table and gives it a
-- metatable whose __newindex fails. The refill is raw and protected: no metamethod of the scene's
-- runs inside the host, and the run goes on.
-- run: --time 1 --quiet
-- expect: refilled 60 times
local count = 0
function PopulateWorld(world)
  local b = world:add_circle{ radius = 1 }
  world:add_force{ body = b, evaluate = function(s)
    count = count + 1
    assert(s.position.x == s.position.x and s.mass > 0, "state not refilled")
    for k in pairs(s) do s[k] = nil end
    setmetatable(s, { __newindex = function() error("metamethod ran inside the host") end,
                      __index = function() error("metamethod ran inside the host") end })
    return 0, 0
  end }
  world.integrator = "semi_implicit_euler"
end
function Check() print("refilled " .. count .. " times") end
