-- Projectile with linear drag F = −b v (docs/design/accuracy.md §3.2), the built-in damper. With τ = m/b:
--   x(t) = v0x τ (1 − e^{−t/τ}),   y(t) = τ (v0y + g τ)(1 − e^{−t/τ}) − g τ t
-- m = 1 kg, b = 0.5 N·s/m (τ = 2 s), v0 = (20, 20) m/s: x(2) = 25.2848223531, y(2) = 10.8541626661.
scene = { sleeping = false, title = "Projectile with linear drag", dt = 1 / 60, duration = 3, camera = { center = {15, 5}, height = 20 } }

local g, m, b = 9.80665, 1.0, 0.5
local tau = m / b
local v0x, v0y = 20.0, 20.0

accuracy = {
  group = "smooth",
  t_end = 3,
  reference_length = 1,  -- absolute error [m]
  metrics = { "velocity" },
  reference_speed = 1,
  note = "velocity-dependent force: RK4 order 4, the Euler variants order 1",
}

function PopulateWorld(world)
  local ball = world:add_circle{ name = "ball", radius = 0.1, mass = m, velocity = {v0x, v0y} }
  world:add_damper{ body = ball, coefficient = b }
end

function Exact(t)
  local e = math.exp(-t / tau)
  return { ball = {
    position = { v0x * tau * (1 - e), tau * (v0y + g * tau) * (1 - e) - g * tau * t },
    velocity = { v0x * e, (v0y + g * tau) * e - g * tau },
  } }
end
