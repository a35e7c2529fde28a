--- Readings the joint scenes watch every step: how far a joint's two anchors have drifted apart
--- (a pin, weld or wheel axle keeps them together) and how far a joint's angle is past its limits.
---     local watch = require "watch"
---     worst = math.max(worst, watch.gap(joints))
local M = {}

--- The largest distance between the two anchors of any of the joints, m.
function M.gap(joints)
  local worst = 0
  for _, j in ipairs(joints) do worst = math.max(worst, (j.anchor_a - j.anchor_b):length()) end
  return worst
end

--- The largest amount by which a revolute joint's angle is outside [lower_angle, upper_angle], rad
--- (0 when every limited joint is within its limits).
function M.past_limits(joints)
  local worst = 0
  for _, j in ipairs(joints) do
    if j.enable_limit then worst = math.max(worst, j.lower_angle - j.angle, j.angle - j.upper_angle) end
  end
  return worst
end

return M
