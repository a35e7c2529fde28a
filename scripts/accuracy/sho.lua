-- Undamped spring–mass, Hooke F = −k x (docs/design/accuracy.md §3.3): x(t) = x0 cos ωt + (v0/ω) sin ωt.
-- m = 1 kg, k = 4π² N/m (1 Hz), x0 = 0.1 m, v0 = 0, T = 10.1 s (off the special phases where
-- semi-implicit Euler's final-time error looks second order). Exact: x(10.1) = 0.0809016994374951.
-- The spring runs from a fixed anchor at the origin with rest length 0, so F = −k x in the plane.
scene = { sleeping = false, title = "Spring–mass (undamped)", gravity = {0, 0}, dt = 1 / 60, duration = 10.1,
          camera = { center = {0, 0}, height = 0.5 } }

local m, k, x0 = 1.0, 4 * math.pi ^ 2, 0.1
local w = math.sqrt(k / m)

accuracy = {
  group = "smooth",
  t_end = 10.1,
  reference_length = x0,  -- the amplitude [m]
  metrics = { "energy", "velocity" },
  reference_speed = w * x0,
  long_run = 1000,
  note = "E0 = 0.19739 J; explicit Euler gains (1 + (ωh)²) per step",
}

function PopulateWorld(world)
  local ball = world:add_circle{ name = "ball", radius = 0.02, mass = m, position = {x0, 0} }
  world:add_spring{ a = ball, anchor = {0, 0}, stiffness = k, rest_length = 0 }
end

function Exact(t)
  return { ball = { position = { x0 * math.cos(w * t), 0 }, velocity = { -x0 * w * math.sin(w * t), 0 } } }
end
