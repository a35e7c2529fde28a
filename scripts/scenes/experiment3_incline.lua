-- Experiment 3 of the thesis (docs/design/thesis.md §12.3): four squares dropped on an inclined plane, each with
-- a different dynamic friction. The one with the lowest friction slides fastest; the one whose
-- friction exceeds the slope's tangent stops soon after landing. While sliding, a square's
-- acceleration along the slope is a = g (sin θ − f cos θ) (docs/design/thesis.md §1, §10).
local check = require "check"

local theta = math.rad(25)                   -- tan 25° = 0.466
local frictions = { 0.1, 0.25, 0.4, 0.6 }   -- lowest first: it starts furthest down the slope
local g = 9.80665

scene = { title = "Experiment 3: squares sliding down an incline", duration = 3,
          camera = { center = {-4, -2}, height = 16 } }

local down = vec2(-math.cos(theta), -math.sin(theta))  -- unit vector down the slope
local normal = vec2(-math.sin(theta), math.cos(theta))
local start, speed_at_2s = {}, {}

function PopulateWorld(world)
  world:add_box{ name = "incline", width = 40, height = 1, angle = theta, static = true,
                 friction = 1, static_friction = 1 }
  for i, f in ipairs(frictions) do
    -- On the slope's top face (0.5 m above its centre line), 0.3 m up in the air, 2.5 m apart.
    local along = 6 - 2.5 * i
    local position = down * along + normal * (0.5 + 0.5 + 0.3)
    -- The pair's friction is sqrt(f_incline · f_square) = f with the incline's f = 1.
    local square = world:add_box{ name = "f=" .. f, width = 1, height = 1, position = position, angle = theta,
                                  friction = f * f, static_friction = f * f }
    start[i] = square.position
  end
end

function OnStep(world, dt)
  if math.abs(world.time - 2) < dt / 2 then
    for i, f in ipairs(frictions) do speed_at_2s[i] = world:find("f=" .. f).velocity:dot(down) end
  end
end

function Check(world)
  local distance = {}
  for i, f in ipairs(frictions) do
    local square = world:find("f=" .. f)
    distance[i] = (square.position - start[i]):dot(down)
    print(string.format("friction %.2f: slid %.3f m, speed %.3f m/s", f, distance[i], square.velocity:dot(down)))
  end
  for i = 1, #frictions - 1 do
    check.greater(string.format("slide distance with friction %.2f minus with %.2f", frictions[i], frictions[i + 1]),
                  distance[i] - distance[i + 1], 0.1)
  end
  -- The highest friction (0.6 > tan 25°) has stopped and stays.
  local last = world:find("f=" .. frictions[#frictions])
  check.less("speed of the square with friction 0.6", last.velocity:length(), 1e-3)
  -- The sliding ones accelerate at g (sin θ − f cos θ) during the last second (1st-order error).
  for i = 1, 3 do
    local f = frictions[i]
    local a = (world:find("f=" .. f).velocity:dot(down) - speed_at_2s[i]) / 1.0
    check.near(string.format("acceleration with friction %.2f", f), a, g * (math.sin(theta) - f * math.cos(theta)), 0.02)
  end
end
