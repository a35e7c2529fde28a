-- A spring pendulum (elastic pendulum): a 1 kg ball on an undamped spring from a fixed anchor,
-- swinging and bouncing under gravity. Nothing dissipates, so the total energy (kinetic, gravity,
-- spring) is conserved; with RK4 at 60 Hz the integrator's own loss is tiny (a⁶/72 per step for
-- a = ωh = 0.12, docs/design/accuracy.md §2). The energy is printed every second.
local check = require "check"

scene = { title = "Spring pendulum", duration = 20, integrator = "rk4", camera = { center = {0, 1}, height = 7 } }

local e0, worst, leftmost = 0, 0, math.huge

function PopulateWorld(world)
  local ball = world:add_circle{ name = "ball", radius = 0.2, mass = 1, position = {1.5, 2.0} }
  world:add_spring{ a = ball, anchor = {0, 3}, stiffness = 50, rest_length = 1.5 }
  e0 = world:kinetic_energy() + world:potential_energy()
end

function OnStep(world, dt)
  local e = world:kinetic_energy() + world:potential_energy()
  worst = math.max(worst, math.abs(e / e0 - 1))
  leftmost = math.min(leftmost, world:find("ball").position.x)
  if world.step_count % 60 == 0 then
    local p = world:find("ball").position
    print(string.format("t=%4.1f  ball (%6.3f, %6.3f)  energy %.9f J", world.time, p.x, p.y, e))
  end
end

function Check(world)
  print(string.format("largest relative energy change: %.2e", worst))
  check.less("largest relative change of the total energy over 20 s", worst, 1e-5)
  -- It really swings: released 1.5 m right of the anchor, it reaches the other side.
  check.less("leftmost x of the ball", leftmost, -0.5)
end
