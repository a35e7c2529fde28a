-- A rigid pendulum on a revolute joint, released from rest at θ0 = 2 rad (115°) from the hanging
-- position: the joints' reference problem (docs/integrators.md, "Joints inside the integrator").
-- The bob is a disc of m = 1 kg, radius r = 0.1 m, its centre L = 1 m from a pin to the world at
-- the origin. About the pin I_p = ½ m r² + m L², so I_p θ'' = −m g L sin θ, ω0² = m g L / I_p.
-- Released from rest, sin(θ/2) = k sn(K − ω0 t, k) with k = sin(θ0/2) (Jacobi's sn with modulus k),
-- and the period is the exact large-amplitude one, T = 4 K(k) / ω0, K the complete elliptic integral
-- of the first kind: K(k) = π / (2 AGM(1, √(1 − k²))) (scripts/elliptic.lua). Here ω0 = 3.124291
-- rad/s, K = 2.087438, T = 2.672527 s (the small-angle 2π/ω0 = 2.011080 s is 25 % short). The run is
-- one period (t_end = 2.7 s). The bob touches nothing, so the joint is integrated with it: its force
-- solved at every stage, the bob projected back onto its circle after each step, and every
-- integrator keeps its order (docs/integrators.md). pendulum_small.lua and pendulum_large.lua are
-- the same pendulum at θ0 = 0.2 and 3.0 rad.
local elliptic = require "elliptic"

local m, r, L, g, theta0 = 1.0, 0.1, 1.0, 9.81, 2.0
scene = { sleeping = false, title = "Pendulum on a revolute joint (θ0 = 2 rad)", gravity = { 0, -g }, dt = 1 / 60,
          duration = 2.7, camera = { center = {0, -0.3}, height = 3 } }

local I_p = 0.5 * m * r * r + m * L * L
local w0 = math.sqrt(m * g * L / I_p)
local swing = elliptic.pendulum{ theta0 = theta0, omega0 = w0 }

accuracy = {
  group = "mechanism",
  t_end = 2.7,  -- one period and a little
  reference_length = L,  -- the arm [m]
  metrics = { "energy", "velocity" },
  reference_speed = w0 * L,
  period = swing.period,
  period_body = "bob",
  note = string.format("T = 4K(k)/ω0 = %.6f s, k = sin 1; E0 = %.5f J", swing.period, -m * g * L * math.cos(theta0)),
}

function PopulateWorld(world)
  local bob = world:add_circle{ name = "bob", radius = r, mass = m,
                                position = { L * math.sin(theta0), -L * math.cos(theta0) }, angle = theta0 }
  world:add_revolute{ a = bob, anchor = { 0, 0 } }  -- b omitted: pinned to the world
end

function Exact(t)
  local theta, omega = swing.at(t)
  return { bob = { position = { L * math.sin(theta), -L * math.cos(theta) },
                   velocity = { L * omega * math.cos(theta), L * omega * math.sin(theta) },
                   angle = theta, angular_velocity = omega } }
end
