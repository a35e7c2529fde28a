--- A Hooke spring with damping along its axis, written only against rigidlab's public Lua API:
--- the worked example of a custom force. It follows the same law as world:add_spring
---     F_a = [k (L - L0) + c (v_b - v_a)·u] u,   F_b = -F_a,   u = (p_b - p_a) / L
--- and a regression scene (tests/scenes/lua_spring_twin.lua) checks that both give the same
--- trajectory. Use:
---     local spring = require "forces.spring"
---     spring.add(world, { a = ball, anchor = {0, 10}, stiffness = 50, rest_length = 2, damping = 0.5 })
---     spring.add(world, { a = ball, b = box, local_a = {0, 0}, local_b = {0.3, 0.3}, stiffness = 20 })
--- Options are those of world:add_spring. With RK4 each side is evaluated at every stage with
--- both bodies' stage states (add_force's `other`), so the spring keeps RK4's fourth order.
local M = {}

local known = { a = true, b = true, anchor = true, local_a = true, local_b = true,
                stiffness = true, rest_length = true, damping = true }

local function check_options(o)
  if type(o) ~= "table" then error("spring.add: expects a table of options, got " .. type(o), 3) end
  local unknown = {}
  for key in pairs(o) do
    if not known[key] then unknown[#unknown + 1] = tostring(key) end
  end
  table.sort(unknown)  -- the same message whatever the table order
  if #unknown > 0 then error("spring.add: unknown option '" .. unknown[1] .. "'", 3) end
end

local function xy(v, name)
  if v == nil then return 0.0, 0.0 end
  if type(v) == "table" then
    local x, y = v.x or v[1], v.y or v[2]
    if type(x) == "number" and type(y) == "number" then return x, y end
  end
  error("spring.add: " .. name .. " must be a vector {x, y}", 4)
end

local function number(v, name, default)
  if v == nil and default ~= nil then return default end
  if type(v) ~= "number" or v ~= v or v < 0 or v == math.huge then
    error("spring.add: " .. name .. " must be a number >= 0, got " .. tostring(v), 4)
  end
  return v
end

-- World position and velocity of the body point (lx, ly) for a state s (a force's argument or a
-- body: both have position, velocity, center, angle, angular_velocity).
local function point(s, lx, ly)
  local c, sn = math.cos(s.angle), math.sin(s.angle)
  local px = s.position.x + c * lx - sn * ly
  local py = s.position.y + sn * lx + c * ly
  local w = s.angular_velocity
  local rx, ry = px - s.center.x, py - s.center.y
  return px, py, s.velocity.x - w * ry, s.velocity.y + w * rx, rx, ry
end

function M.add(world, o)
  check_options(o)
  local k = number(o.stiffness, "stiffness")
  local c = number(o.damping, "damping", 0.0)
  local lax, lay = xy(o.local_a, "local_a")
  local lbx, lby = xy(o.local_b, "local_b")
  if (o.b == nil) == (o.anchor == nil) then
    error("spring.add: give either b (a body) or anchor (a point)", 2)
  end

  local handles = {}
  if o.anchor ~= nil then
    local ax, ay = xy(o.anchor, "anchor")
    local px, py = point(o.a, lax, lay)
    local rest = number(o.rest_length, "rest_length", math.sqrt((ax - px) ^ 2 + (ay - py) ^ 2))
    handles[1] = world:add_force{ body = o.a, evaluate = function(s)
      local x, y, vx, vy, rx, ry = point(s, lax, lay)
      local dx, dy = ax - x, ay - y
      local length = math.sqrt(dx * dx + dy * dy)
      if length == 0 then return 0, 0, 0 end
      local ux, uy = dx / length, dy / length
      local tension = k * (length - rest) - c * (vx * ux + vy * uy)
      local fx, fy = tension * ux, tension * uy
      return fx, fy, rx * fy - ry * fx
    end }
  else
    local px, py = point(o.a, lax, lay)
    local qx, qy = point(o.b, lbx, lby)
    local rest = number(o.rest_length, "rest_length", math.sqrt((qx - px) ^ 2 + (qy - py) ^ 2))
    -- One force per end; each sees its own stage state (s) and the other end's (t).
    local function side(lsx, lsy, lox, loy)
      return function(s, t)
        local x, y, vx, vy, rx, ry = point(s, lsx, lsy)
        local x2, y2, vx2, vy2 = point(t, lox, loy)
        local dx, dy = x2 - x, y2 - y
        local length = math.sqrt(dx * dx + dy * dy)
        if length == 0 then return 0, 0, 0 end
        local ux, uy = dx / length, dy / length
        local tension = k * (length - rest) + c * ((vx2 - vx) * ux + (vy2 - vy) * uy)
        local fx, fy = tension * ux, tension * uy
        return fx, fy, rx * fy - ry * fx
      end
    end
    handles[1] = world:add_force{ body = o.a, other = o.b, evaluate = side(lax, lay, lbx, lby) }
    handles[2] = world:add_force{ body = o.b, other = o.a, evaluate = side(lbx, lby, lax, lay) }
  end

  local spring = { forces = handles }
  function spring.remove()
    for _, h in ipairs(handles) do
      if not h.removed then h:remove() end
    end
  end
  return spring
end

return M
