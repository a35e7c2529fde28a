-- A body with linear and angular damping thrown under gravity: v' = g − c v, ω' = −c_ω ω, so
--   v(t) = v∞ + (v0 − v∞) e^(−c t),  v∞ = g / c,   x(t) = x0 + v∞ t + (v0 − v∞)(1 − e^(−c t))/c
--   θ(t) = ω0 (1 − e^(−c_ω t)) / c_ω
-- The damping (BodyDef::linear_damping, angular_damping) is evaluated at every stage of RK4, so it
-- keeps order 4 (as a damper written in Lua does, drag_projectile.lua); the Euler methods take it
-- implicitly, first order.
local c, c_w, g = 0.5, 0.3, 9.81
local v0, w0 = { 10, 10 }, 4.0
scene = { sleeping = false, title = "A damped body thrown under gravity (linear_damping)", gravity = { 0, -g },
          dt = 1 / 60, duration = 3, camera = { center = {12, 3}, height = 16 } }

accuracy = {
  group = "smooth",
  t_end = 3,
  reference_length = 10,
  metrics = { "velocity" },
  reference_speed = 10,
  note = string.format("c = %g 1/s, c_ω = %g 1/s: terminal speed g/c = %.3f m/s", c, c_w, g / c),
}

function PopulateWorld(world)
  world:add_circle{ name = "ball", radius = 0.2, mass = 1, position = { 0, 0 }, velocity = v0, angular_velocity = w0,
                    linear_damping = c, angular_damping = c_w }
end

function Exact(t)
  local e = math.exp(-c * t)
  local vinf = { 0, -g / c }
  local x, v = {}, {}
  for i = 1, 2 do
    v[i] = vinf[i] + (v0[i] - vinf[i]) * e
    x[i] = vinf[i] * t + (v0[i] - vinf[i]) * (1 - e) / c
  end
  return { ball = { position = x, velocity = v, angle = w0 * (1 - math.exp(-c_w * t)) / c_w } }
end
