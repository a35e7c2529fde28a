-- Newton's cradle built of joints: each ball hangs on a rigid distance joint from a point 1.5 m above
-- it (a massless rod from the point to the ball's centre), restitution 1, no friction. The left
-- ball swings in from 25°; its momentum passes through the three at rest to the right one, which
-- swings out to the height the left one fell from while the others stay put. A distance joint
-- pulls along the rod, through the ball's centre, and the balls are frictionless, so no ball turns:
-- each is a point mass on a rod, and the left ball reaches √(2 g h) (h its drop). The rods take a
-- little energy on the way (in proportion to h, as any rigid joint of this solver,
-- docs/integrators.md), so the right ball's rise is compared both with the release height and with
-- that of a lone ball swung from the same angle on its own rod, which loses the same. As in
-- newtons_cradle.lua (which hangs its balls on stiff springs) the balls hang 1 cm apart, more than a
-- ball moves in a step, so the impacts come one pair at a time.
local check = require "check"
local watch = require "watch"

scene = { title = "Newton's cradle (revolute joints)", dt = 1/240, duration = 1.4, camera = { center = {0.8, 1}, height = 3 } }

local count, r, rod, spacing, release = 5, 0.2, 1.5, 0.41, math.rad(25)
local rods, balls = {}, {}
local lone, lone_pivot = nil, vec2(-3, rod)
local drop, rise, lone_rise, first_after, impact_speed, passed_speed, stretch = 0, 0, 0, nil, 0, 0, 0
local momentum_in, momentum_out = 0, 0

function PopulateWorld(world)
  for k = 1, count do
    local pivot = vec2((k - 1) * spacing, rod)
    local swing = k == 1 and -release or 0
    balls[k] = world:add_circle{ radius = r, mass = 1, restitution = 1, friction = 0,
                                 position = pivot + vec2(0, -rod):rotated(swing) }
    rods[k] = world:add_distance{ a = balls[k], anchor_b = pivot }  -- rigid, its length now
  end
  drop = balls[1].position.y
  lone = world:add_circle{ radius = r, mass = 1, friction = 0, position = lone_pivot + vec2(0, -rod):rotated(-release) }
  rods[count + 1] = world:add_distance{ a = lone, anchor_b = lone_pivot }
end

function OnStep(world, dt)
  local left, right = balls[1], balls[count]
  impact_speed = math.max(impact_speed, left.velocity:length())
  rise = math.max(rise, right.position.y)
  if lone.position.x > lone_pivot.x then lone_rise = math.max(lone_rise, lone.position.y) end
  -- Just after the first impact the left ball is (nearly) at rest; the momentum it brought in is
  -- its largest; the right ball's largest, once it leaves, is what came out.
  if not first_after and balls[2].velocity:length() > 0.1 then first_after = left.velocity:length() end
  momentum_in = math.max(momentum_in, left.mass * left.velocity.x)
  momentum_out = math.max(momentum_out, right.mass * right.velocity.x)
  passed_speed = math.max(passed_speed, right.velocity:length())
  for _, j in ipairs(rods) do stretch = math.max(stretch, math.abs(j.translation - rod)) end
end

function Check(world)
  local g = -world.gravity.y
  local v = math.sqrt(2 * g * drop)
  print(string.format("left ball hit at %.4f m/s (√(2 g h) = %.4f), kept %.4f m/s; right ball left at %.4f m/s; " ..
                      "momentum in %.4f, out %.4f kg·m/s; right ball rose %.5f m, the lone ball %.5f m, of %.5f m; " ..
                      "rods off their length by %.2g m",
                      impact_speed, v, first_after, passed_speed, momentum_in, momentum_out, rise, lone_rise, drop, stretch))
  -- Measured 0.46 % below: the rod's loss.
  check.near("impact speed = √(2 g h)", impact_speed, v, 0.01 * v)
  check.less("the left ball stops at impact", first_after, 0.05 * impact_speed)
  check.near("the momentum passes through to the right ball", momentum_out / momentum_in, 1, 5e-3)
  for k = 2, count - 1 do
    check.less("ball " .. k .. " stays put", balls[k].position.y, 0.02 * drop)
  end
  check.near("the right ball rises as high as the lone ball", rise / lone_rise, 1, 2e-3)
  check.near("the right ball rises to the release height, within 3 %", rise / drop, 1, 0.03)
  check.less("the rods keep their length", stretch, 1e-6)
end
