-- A wheel on its suspension: a 1 kg disc hangs from a static chassis on a wheel joint with a
-- vertical axis and a spring of 2 Hz, damping ratio 0.1, released at the spring's rest length and
-- turning at 3 rad/s (the wheel turns freely on the joint). Along the axis the spring pulls with
-- −k x − c x', k = m ω², c = 2 m ζ ω (ω = 2π f; the anchor is the disc's centre, so the
-- spring's effective mass is m): a damped oscillator about x_eq = −g/ω²,
--   x(t) = x_eq (1 − e^(−ζωt) (cos ω_d t + ζω/ω_d sin ω_d t)),  ω_d = ω √(1 − ζ²)
-- The spring is a force evaluated at every stage, so RK4 keeps order 4.
local m, r, g, f, zeta, spin = 1.0, 0.3, 9.81, 2.0, 0.1, 3.0
scene = { sleeping = false, title = "Wheel on a sprung suspension (wheel joint)", gravity = { 0, -g }, dt = 1 / 60,
          duration = 3, camera = { center = {0, -0.5}, height = 3 } }

local omega = 2 * math.pi * f
local wd = omega * math.sqrt(1 - zeta * zeta)
local x_eq = -g / (omega * omega)

accuracy = {
  group = "mechanism",
  t_end = 3,
  reference_length = math.abs(x_eq),
  metrics = { "velocity" },
  reference_speed = math.abs(x_eq) * omega,
  note = string.format("f = %g Hz, ζ = %g: x_eq = −g/ω² = %.6f m", f, zeta, x_eq),
}

function PopulateWorld(world)
  local chassis = world:add_box{ name = "chassis", width = 1, height = 0.2, position = { 0, 0.5 }, static = true }
  local wheel = world:add_circle{ name = "wheel", radius = r, mass = m, position = { 0, 0 }, angular_velocity = spin }
  world:add_wheel{ a = chassis, b = wheel, anchor = { 0, 0 }, axis = { 0, 1 }, spring_hertz = f, spring_damping = zeta }
end

function Exact(t)
  local e = math.exp(-zeta * omega * t)
  local x = x_eq * (1 - e * (math.cos(wd * t) + zeta * omega / wd * math.sin(wd * t)))
  local v = x_eq * e * (omega * omega / wd) * math.sin(wd * t)
  return { wheel = { position = { 0, x }, velocity = { 0, v }, angle = spin * t } }
end
