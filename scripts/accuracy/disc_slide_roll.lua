-- A solid disc launched sliding on a flat floor starts to roll (docs/design/accuracy.md §3.9): m = 1 kg,
-- r = 0.5 m, v0 = 6 m/s, ω0 = 0, μ = 0.3. Friction gives v = v0 − μ g t and ω r = 2 μ g t (ω < 0,
-- clockwise, for motion to the right) until rolling starts at t* = v0/(3 μ g) = 0.6798108087 s with
-- v_f = 2 v0/3 = 4 m/s and |ω_f| = v_f/r = 8 rad/s; 6 J of the 18 J are lost to friction.
scene = { sleeping = false, title = "Disc: sliding, then rolling", dt = 1 / 60, duration = 2,
          camera = { center = {5, 0}, height = 6 } }

local g, m, r, v0, mu = 9.80665, 1.0, 0.5, 6.0, 0.3
local ts = v0 / (3 * mu * g)
local vf = 2 * v0 / 3

accuracy = {
  group = "contact",
  expected_order = { rk4 = 1 },  -- contacts once per step: O(h) whatever the integrator
  t_end = 2,
  reference_length = 1,  -- absolute error [m]
  metrics = { "velocity" },
  reference_speed = vf,
  note = "friction switches from sliding to rolling at t* = 0.680 s",
}

function PopulateWorld(world)
  world:add_box{ name = "floor", width = 40, height = 1, position = {10, -0.5}, static = true, friction = mu }
  world:add_circle{ name = "disc", radius = r, mass = m, position = {0, r}, velocity = {v0, 0}, friction = mu }
end

function Exact(t)
  local x, v, angle, w
  if t <= ts then
    x, v = v0 * t - 0.5 * mu * g * t * t, v0 - mu * g * t
    angle, w = -(mu * g / r) * t * t, -(2 * mu * g / r) * t
  else
    local xs = v0 * ts - 0.5 * mu * g * ts * ts
    x, v = xs + vf * (t - ts), vf
    angle, w = -(mu * g / r) * ts * ts - (vf / r) * (t - ts), -vf / r
  end
  return { disc = { position = {x, r}, velocity = {v, 0}, angle = angle, angular_velocity = w } }
end
