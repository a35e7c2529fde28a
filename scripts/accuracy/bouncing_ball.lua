-- A ball dropped from a gap h0 = 1 m onto a floor with restitution e = 0.8 (docs/design/accuracy.md §3.12).
-- First impact at t1 = √(2 h0/g) = 0.4516007558 s at 4.4286905514 m/s; after bounce n the apex is
-- e^{2n} h0 (0.64 m after the first); the second impact is at 1.1741619650 s. Each impact is
-- located inside its step (impacts = "located"); with impacts handled once per step the error was
-- O(h) even where free flight is exact (RK4).
scene = { sleeping = false, title = "Bouncing ball, e = 0.8", dt = 1 / 60, duration = 2,
          camera = { center = {0, 0.6}, height = 1.6 } }

local g, h0, e, r = 9.80665, 1.0, 0.8, 0.1

accuracy = {
  group = "impact",
  -- Located impacts: RK4 integrates each parabola exactly and the bounce happens at the moment of
  -- contact, so it is exact to round-off (measured: at most 8.8e-14 of h0; 0.049 at 1/60 with
  -- impacts once per step); the Euler family keeps its own order 1.
  expected_order = { rk4 = "exact" },
  t_end = 2,
  reference_length = h0,  -- the drop height [m]
  metrics = { "velocity" },
  reference_speed = math.sqrt(2 * g * h0),
  note = "three impacts in 2 s; apex after the first 0.64 m",
}

function PopulateWorld(world)
  world:add_box{ name = "floor", width = 4, height = 1, position = {0, -0.5}, static = true, restitution = e }
  world:add_circle{ name = "ball", radius = r, mass = 1, position = {0, r + h0}, restitution = e }
end

-- Height of the ball's bottom above the floor and its vertical velocity at time t: a free fall to
-- the first impact, then parabolas of take-off speed e^n v1.
local function flight(t)
  local t1 = math.sqrt(2 * h0 / g)
  if t <= t1 then return h0 - 0.5 * g * t * t, -g * t end
  local start, speed = t1, e * g * t1
  while true do
    local duration = 2 * speed / g
    if t <= start + duration then
      local s = t - start
      return speed * s - 0.5 * g * s * s, speed - g * s
    end
    start, speed = start + duration, e * speed
  end
end

function Exact(t)
  local y, v = flight(t)
  return { ball = { position = {0, r + y}, velocity = {0, v} } }
end
