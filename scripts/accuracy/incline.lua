-- A block sliding down a 30° incline with Coulomb friction μ = 0.2 (docs/design/accuracy.md §3.8). Released at
-- rest; tan 30° = 0.577 > μ, so it slides with a = g (sin θ − μ cos θ) = 3.2047633948 m/s² and
-- s(t) = ½ a t²: s(2) = 6.4095267896 m down the slope. Contacts are handled once per step, so the
-- error is O(h) whatever the integrator (semi-implicit Euler ideally ½ a t (t + h)).
scene = { sleeping = false, title = "Block on a 30° incline, μ = 0.2", dt = 1 / 60, duration = 2,
          camera = { center = {0, 0}, height = 12 } }

local g, theta, mu = 9.80665, math.rad(30), 0.2
local a = g * (math.sin(theta) - mu * math.cos(theta))
local d = { math.cos(theta), -math.sin(theta) }  -- down the slope
local n = { math.sin(theta), math.cos(theta) }   -- surface normal
local half = 0.25                                -- half the block's side [m]
-- Start 5 m up the slope from the middle of the incline, resting on its top face (0.5 m above the
-- incline's centre line).
local start = { n[1] * (0.5 + half) - 5 * d[1], n[2] * (0.5 + half) - 5 * d[2] }

accuracy = {
  group = "contact",
  expected_order = { rk4 = 1 },  -- contacts once per step: O(h) whatever the integrator
  t_end = 2,
  reference_length = 1,  -- absolute error [m]
  metrics = { "velocity" },
  reference_speed = 1,
  note = "Coulomb friction, contacts once per step: O(h)",
}

function PopulateWorld(world)
  world:add_box{ name = "incline", width = 20, height = 1, angle = -theta, static = true, friction = mu }
  world:add_box{ name = "block", width = 2 * half, height = 2 * half, angle = -theta, position = start,
                 mass = 1, friction = mu }
end

function Exact(t)
  local s, v = 0.5 * a * t * t, a * t
  return { block = { position = { start[1] + s * d[1], start[2] + s * d[2] }, velocity = { v * d[1], v * d[2] },
                     angle = -theta, angular_velocity = 0 } }
end
