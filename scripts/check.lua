--- Assertions for Check(world) hooks: each failure is one error naming the quantity, the value
--- found and the value expected, located at the line of the Check that called it.
---     local check = require "check"
---     check.near("ball x", ball.position.x, 2.5, 1e-9)
local M = {}

local function fmt(x) return string.format("%.10g", x) end

--- |actual - expected| <= tolerance
function M.near(name, actual, expected, tolerance)
  if type(actual) ~= "number" or not (math.abs(actual - expected) <= tolerance) then
    error(string.format("%s = %s, expected %s within %s (off by %s)", name, tostring(actual), fmt(expected),
                        fmt(tolerance), type(actual) == "number" and fmt(math.abs(actual - expected)) or "?"), 2)
  end
end

--- actual < limit
function M.less(name, actual, limit)
  if not (actual < limit) then
    error(string.format("%s = %s, expected below %s", name, fmt(actual), fmt(limit)), 2)
  end
end

--- actual > limit
function M.greater(name, actual, limit)
  if not (actual > limit) then
    error(string.format("%s = %s, expected above %s", name, fmt(actual), fmt(limit)), 2)
  end
end

--- condition is true
function M.that(name, condition, detail)
  if not condition then error(name .. (detail and (": " .. detail) or ""), 2) end
end

return M
