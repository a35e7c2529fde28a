-- Newton's cradle built of joints: each ball hangs on a revolute pin 1.5 m above it (a massless
-- rigid rod: the pin holds the ball's centre at a fixed distance), restitution 1, no friction. The
-- left ball swings in from 25°; its momentum passes through the three at rest to the right one,
-- which swings out to the height the left one fell from while the others stay put. A pinned ball
-- turns with its rod, so each is a compound pendulum of inertia m L² + I about its pin, the same
-- for all five: the impacts exchange their velocities as between equal point masses, and the left
-- ball reaches √(2 g h / (1 + I / (m L²))). The pins take a little energy on the way (in proportion
-- to h, as any pinned pendulum of this solver: measured 0.9 % of the kinetic energy in a quarter
-- swing at h = 1/240), so the right ball's rise is compared with that of a lone ball swung from
-- the same angle on its own pin, which loses the same. As in
-- newtons_cradle.lua (which hangs its balls on stiff springs) the balls hang 1 cm apart, more than a
-- ball moves in a step, so the impacts come one pair at a time.
local check = require "check"
local watch = require "watch"

scene = { title = "Newton's cradle (revolute joints)", dt = 1/240, duration = 1.4, camera = { center = {0.8, 1}, height = 3 } }

local count, r, rod, spacing, release = 5, 0.2, 1.5, 0.41, math.rad(25)
local pins, balls = {}, {}
local lone, lone_pivot = nil, vec2(-3, rod)
local drop, rise, lone_rise, first_after, impact_speed = 0, 0, 0, nil, 0

function PopulateWorld(world)
  for k = 1, count do
    local pivot = vec2((k - 1) * spacing, rod)
    local swing = k == 1 and -release or 0
    balls[k] = world:add_circle{ radius = r, mass = 1, restitution = 1, friction = 0,
                                 position = pivot + vec2(0, -rod):rotated(swing) }
    pins[k] = world:add_revolute{ a = balls[k], anchor = pivot }
  end
  drop = balls[1].position.y
  lone = world:add_circle{ radius = r, mass = 1, friction = 0, position = lone_pivot + vec2(0, -rod):rotated(-release) }
  pins[count + 1] = world:add_revolute{ a = lone, anchor = lone_pivot }
end

function OnStep(world, dt)
  impact_speed = math.max(impact_speed, balls[1].velocity:length())
  rise = math.max(rise, balls[count].position.y)
  if lone.position.x > lone_pivot.x then lone_rise = math.max(lone_rise, lone.position.y) end
  -- Just after the first impact the left ball is (nearly) at rest.
  if not first_after and balls[2].velocity:length() > 0.1 then first_after = balls[1].velocity:length() end
end

function Check(world)
  local g = -world.gravity.y
  local v = math.sqrt(2 * g * drop / (1 + balls[1].inertia / (balls[1].mass * rod * rod)))
  print(string.format("left ball hit at %.4f m/s (%.4f); kept %.4f m/s; right ball rose %.5f m, the lone ball %.5f m, of %.5f m",
                      impact_speed, v, first_after, rise, lone_rise, drop))
  -- Measured 0.46 % below: the pin's loss.
  check.near("impact speed = √(2 g h / (1 + I / (m L²)))", impact_speed, v, 0.01 * v)
  check.less("the left ball stops at impact", first_after, 0.05 * impact_speed)
  check.near("the right ball rises as high as the lone ball", rise / lone_rise, 1, 2e-3)
  check.greater("which is nearly the release height", lone_rise / drop, 0.97)
  for k = 2, count - 1 do
    check.less("ball " .. k .. " stays put", balls[k].position.y, 0.02 * drop)
  end
  check.less("the rods keep their length", watch.gap(pins), 1e-6)
end
