--- A linear and angular damper, F = -c v and torque = -c_w w, written only against the public
--- Lua API: the twin of world:add_damper (tests/scenes/lua_damper_twin.lua compares them).
---     local damper = require "forces.damper"
---     damper.add(world, { body = ball, coefficient = 0.1, angular_coefficient = 0.01 })
local M = {}

function M.add(world, o)
  if type(o) ~= "table" then error("damper.add: expects a table of options", 2) end
  for key in pairs(o) do
    if key ~= "body" and key ~= "coefficient" and key ~= "angular_coefficient" then
      error("damper.add: unknown option '" .. tostring(key) .. "'", 2)
    end
  end
  local c, cw = o.coefficient, o.angular_coefficient or 0.0
  if type(c) ~= "number" or c < 0 or c ~= c then
    error("damper.add: coefficient must be a number >= 0, got " .. tostring(c), 2)
  end
  if type(cw) ~= "number" or cw < 0 or cw ~= cw then
    error("damper.add: angular_coefficient must be a number >= 0, got " .. tostring(cw), 2)
  end
  return world:add_force{ body = o.body, evaluate = function(s)
    return -c * s.velocity.x, -c * s.velocity.y, -cw * s.angular_velocity
  end }
end

return M
