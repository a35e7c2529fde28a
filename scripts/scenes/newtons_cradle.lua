-- Newton's cradle: five 1 kg balls on 2 m pendulum strings (stiff springs), restitution 1, no
-- friction. The first ball is pulled 30° aside and released; it stops at impact and the last ball
-- swings out to the same height. The balls hang 2 cm apart, more than a ball travels in one step
-- (2.3 m/s × 1/240 s ≈ 1 cm), so the collisions are a sequence of two-ball impacts, the case a
-- sequential-impulse solver gets right (docs/design/accuracy.md §3.10); touching balls would meet all at once.
local check = require "check"

local n, radius, length, gap = 5, 0.25, 2.0, 0.02
local top = 4.0
local lift = math.rad(30)

scene = { title = "Newton's cradle", dt = 1/240, duration = 1.6, camera = { center = {1, 2.8}, height = 3.5 } }

local balls, start_height, highest = {}, 0, 0

function PopulateWorld(world)
  for i = 1, n do
    local x = (i - 1) * (2 * radius + gap)
    local anchor = vec2(x, top)
    local position = anchor + vec2(0, -length)
    if i == 1 then position = anchor + vec2(-math.sin(lift), -math.cos(lift)) * length end
    local ball = world:add_circle{ name = "ball" .. i, radius = radius, mass = 1, position = position,
                                   restitution = 1, friction = 0 }
    -- A stiff string: ω = √(k/m) = 100 rad/s, ω·dt = 0.42.
    world:add_spring{ a = ball, anchor = anchor, stiffness = 1e4, rest_length = length }
    balls[i] = ball
  end
  start_height = balls[1].position.y
end

function OnStep(world, dt)
  highest = math.max(highest, balls[n].position.y)
end

function Check(world)
  local rise = highest - (top - length)
  local drop = start_height - (top - length)
  print(string.format("first ball released %.4f m up; last ball rose %.4f m (%.1f %%)", drop, rise, 100 * rise / drop))
  check.near("height the last ball reaches, as a fraction of the release height", rise / drop, 1.0, 0.015)
  for i = 2, n - 1 do
    check.less("height reached by middle ball " .. i, balls[i].position.y - (top - length), 0.02 * drop)
  end
end
