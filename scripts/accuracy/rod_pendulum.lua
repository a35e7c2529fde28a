-- A rod on a pin, sent over the top: the planar counterpart of a conical pendulum, a body that turns
-- for ever about a pin under gravity. The rod (a 1 m × 0.05 m box of 1 kg) hangs from a pin to the
-- world at its top end and starts hanging straight down, turning at Ω = 2 ω0 / k with k = 0.8:
-- enough to pass over the top. About the pin I_p = m (L² + w²)/12 + m (L/2)², so
-- I_p θ'' = −m g (L/2) sin θ, ω0² = m g L / (2 I_p), and with φ = θ/2 the energy gives
-- φ' = (Ω/2) √(1 − k² sin² φ): θ = 2 am(Ω t / 2, k), Jacobi's amplitude (scripts/elliptic.lua); a
-- turn takes 4 K(k) / Ω. The rod's centre and velocity follow from θ and θ'.
local elliptic = require "elliptic"

local m, L, w, g, k = 1.0, 1.0, 0.05, 9.81, 0.8
scene = { sleeping = false, title = "A rod whirled over the top of its pin", gravity = { 0, -g }, dt = 1 / 60,
          duration = 1, camera = { center = {0, 0}, height = 3 } }

local I_p = m * (L * L + w * w) / 12 + m * (L / 2) ^ 2
local w0 = math.sqrt(m * g * L / (2 * I_p))
local speed = 2 * w0 / k
local whirl = elliptic.whirl{ omega0 = w0, speed = speed }

accuracy = {
  group = "mechanism",
  t_end = 1,  -- a turn and a fifth
  reference_length = L,
  metrics = { "energy" },
  note = string.format("Ω = %.6f rad/s, k = %.1f: a turn every 4K(k)/Ω = %.6f s", speed, k, whirl.period),
}

-- The rod's centre at angle θ from hanging, and its velocity.
local function rod(theta, omega)
  return { position = { 0.5 * L * math.sin(theta), -0.5 * L * math.cos(theta) },
           velocity = { 0.5 * L * omega * math.cos(theta), 0.5 * L * omega * math.sin(theta) },
           angle = theta, angular_velocity = omega }
end

function PopulateWorld(world)
  local start = rod(0, speed)
  local body = world:add_box{ name = "rod", width = w, height = L, mass = m, position = start.position,
                              velocity = start.velocity, angular_velocity = speed }
  world:add_revolute{ a = body, anchor = { 0, 0 } }
end

function Exact(t) return { rod = rod(whirl.at(t)) } end
