--- A ragdoll of revolute joints with limits (neck, shoulders, elbows, hips, knees), as the joint
--- scenes build it (ragdoll_pile.lua, ragdoll_drop.lua). Its parts share a negative group, so its
--- own limbs pass through each other and only the joints hold them, as in Box2D's ragdoll sample.
---     local ragdoll = require "ragdoll"
---     local parts = ragdoll.add(world, vec2(0, 2), 0.3, -1, joints)
local M = {}

--- Adds a ragdoll standing at `origin` (its hips), turned by `turn` [rad], its parts in `group`.
--- Offsets are in the ragdoll's frame, from the hips; limits are of the child's angle relative to
--- its parent. The joints are appended to `joints`; returns the parts (torso first).
function M.add(world, origin, turn, group, joints)
  local parts = {}
  local function place(offset) return origin + vec2(offset[1], offset[2]):rotated(turn) end
  local function part(shape)
    shape.position, shape.angle, shape.group, shape.friction = place(shape.at), turn, group, 0.6
    shape.at = nil
    parts[#parts + 1] = shape.radius and world:add_circle(shape) or world:add_box(shape)
    return parts[#parts]
  end
  local function pin(parent, child, at, lower, upper)
    joints[#joints + 1] = world:add_revolute{ a = parent, b = child, anchor = place(at), lower_angle = lower,
                                              upper_angle = upper }
  end
  local torso = part{ width = 0.4, height = 0.7, at = {0, 0.35} }
  pin(torso, part{ radius = 0.14, at = {0, 0.86} }, {0, 0.72}, -0.6, 0.6)
  for _, side in ipairs{ -1, 1 } do
    local upper_arm = part{ width = 0.1, height = 0.32, at = {0.25 * side, 0.52} }
    pin(torso, upper_arm, {0.25 * side, 0.68}, -2.5, 2.5)
    pin(upper_arm, part{ width = 0.08, height = 0.3, at = {0.25 * side, 0.21} }, {0.25 * side, 0.36}, 0, 2.4)
    local thigh = part{ width = 0.14, height = 0.42, at = {0.1 * side, -0.21} }
    pin(torso, thigh, {0.1 * side, 0}, -1.6, 0.4)
    pin(thigh, part{ width = 0.12, height = 0.4, at = {0.1 * side, -0.62} }, {0.1 * side, -0.42}, -2.4, 0)
  end
  return parts
end

return M
