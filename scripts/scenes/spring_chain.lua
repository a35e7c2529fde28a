-- A chain of five 1 kg balls joined by damped springs, hanging from a fixed anchor. Released with
-- every spring at its rest length, the chain stretches, oscillates and settles. At rest, spring i
-- (counted from the top) carries the weight of the balls below it, so its stretch is
-- (n − i + 1) m g / k (Hooke, docs/design/thesis.md §1); the Check compares every spring with that.
local check = require "check"

local n, m, k, rest, g = 5, 1.0, 200.0, 0.5, 9.80665
-- Sleeping is off: the chain must settle to 1e-6 m, not just below the sleep speed.
scene = { title = "Chain of springs", duration = 20, sleeping = false, camera = { center = {0, 2}, height = 6 } }

local balls = {}

function PopulateWorld(world)
  local above
  for i = 1, n do
    local ball = world:add_circle{ name = "ball" .. i, radius = 0.1, mass = m, position = {0, 4 - i * rest} }
    if above then
      world:add_spring{ a = above, b = ball, stiffness = k, rest_length = rest, damping = 20 }
    else
      world:add_spring{ a = ball, anchor = {0, 4}, stiffness = k, rest_length = rest, damping = 20 }
    end
    balls[i], above = ball, ball
  end
end

function Check(world)
  local y_above = 4
  for i = 1, n do
    local y = balls[i].position.y
    local stretch = (y_above - y) - rest
    check.near("stretch of spring " .. i, stretch, (n - i + 1) * m * g / k, 1e-6)
    check.less("speed of ball " .. i, balls[i].velocity:length(), 1e-5)
    y_above = y
  end
end
