-- scripts/forces/damper.lua against world:add_damper: the same spinning, sliding box twice.
local check = require "check"
local damper = require "forces.damper"

scene = { title = "Lua damper vs built-in damper", gravity = {0, 0}, integrator = "rk4", duration = 3 }

local a, b
local worst = 0

function PopulateWorld(world)
  a = world:add_box{ width = 1, height = 1, position = {0, 0}, velocity = {3, -1}, angular_velocity = 4 }
  b = world:add_box{ width = 1, height = 1, position = {0, 10}, velocity = {3, -1}, angular_velocity = 4 }
  world:add_damper{ body = a, coefficient = 0.8, angular_coefficient = 0.05 }
  damper.add(world, { body = b, coefficient = 0.8, angular_coefficient = 0.05 })
end

function OnStep(world, dt)
  worst = math.max(worst, ((b.position - vec2(0, 10)) - a.position):length(), math.abs(a.angle - b.angle),
                   (a.velocity - b.velocity):length(), math.abs(a.angular_velocity - b.angular_velocity))
end

function Check(world)
  check.less("largest difference between the twins", worst, 1e-12)
  -- v(t) = v0 exp(−c t / m) with m = 1 kg: the damper really acted
  check.near("speed after 3 s", a.velocity:length(), math.sqrt(10) * math.exp(-0.8 * 3), 1e-6)
end
