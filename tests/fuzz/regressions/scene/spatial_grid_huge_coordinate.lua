-- scripts/forces/spring.lua (written in Lua against the public API) against its built-in twin
-- world:add_spring: two copies of the same system, 100 m apart, must follow the same trajectory.
-- Each copy: a box on an anchored spring, and a disc tied to the box by a body-to-body spring, with
-- attachment points off the centres (so torques matter) and damping, under RK4.
local check = require "check"
local spring = require "forces.spring"

scene = { title = "Lua spring vs built-in spring", integrator = "rk4", duration = 5 }

local copies = {}
local worst = 0

local function build(world, x0, use_lua)
  local box = world:add_box{ width = 1, height = 0.5, position = {x0, 3}, angle = 0.3, density = 2 }
  local disc = world:add_circle{ radius = 0.3, position = {x0 + 2, 2}, velocity = {0, 1} }
  local add = use_lua and function(o) return spring.add(world, o) end or function(o) return world:add_spring(o) end
  add{ a = box, anchor = {x0, 6}, local_a = {0.4, 0.2}, stiffness = 666666666666666666666666666666666666666666666666666666666666666666666666666666666666666666666666666666660, rest_length = 2, damping = 0.7 }
  add{ a = box, b = disc, local_a = {-0.3, -0.1}, local_b = {0.1, 0.2}, stiffness = 35, damping = 0.4 }
  return { box, disc }
end

function PopulateWorld(world)
  copies.builtin = build(world, 0, false)
  copies.lua = build(world, 100, true)
end

function OnStep(world, dt)
  for i = 1, 2 do
    local a, b = copies.builtin[i], copies.lua[i]
    local d = (b.position - vec2(100, 0)) - a.position
    worst = math.max(worst, d:length(), math.abs(a.angle - b.angle), (a.velocity - b.velocity):length())
  end
end

function Check(world)
  print(string.format("largest difference between the twins: %.3e", worst))
  check.less("largest difference in position, angle or velocity", worst, 1e-9)
  -- and the system really moved
  check.greater("distance the disc travelled", (copies.builtin[2].position - vec2(2, 2)):length(), 0.5)
end
