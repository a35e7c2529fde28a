-- The pendulum of pendulum_revolute.lua (a 1 kg disc of radius 0.1 m, 1 m from a pin to the world)
-- released from rest at θ0 = 3.0 rad: sin(θ/2) = k sn(K − ω0 t, k), k = sin(θ0/2), T = 4 K(k)/ω0
-- (scripts/elliptic.lua). Integrated with its joint, every integrator keeps its order. The run is
-- the first swing, from θ0 through the bottom to −θ0 (half a period, 2.6 s): a second swing starts
-- again 0.14 rad from the top, where the time to leave it grows without bound with the energy, and
-- the position errors of the sweep's coarse steps (RK4's at 1/30 to 1/240) stop being in their
-- asymptotic range (measured: a fitted 4.74 over a whole period, 3.99 over this swing).
local elliptic = require "elliptic"

local m, r, L, g, theta0 = 1.0, 0.1, 1.0, 9.81, 3.0
scene = { sleeping = false, title = "Pendulum on a revolute joint (θ0 = 3.0 rad)", gravity = { 0, -g }, dt = 1 / 60,
          duration = 2.6, camera = { center = {0, -0.3}, height = 3 } }

local w0 = math.sqrt(m * g * L / (0.5 * m * r * r + m * L * L))
local swing = elliptic.pendulum{ theta0 = theta0, omega0 = w0 }

accuracy = {
  group = "mechanism",
  t_end = 2.6,  -- half a period
  reference_length = L,
  metrics = { "energy" },
  note = string.format("large amplitude: half a period, T/2 = 2K(k)/ω0 = %.6f s, k = sin(θ0/2) = %.6f", swing.period / 2,
                       swing.k),
}

function PopulateWorld(world)
  local bob = world:add_circle{ name = "bob", radius = r, mass = m,
                                position = { L * math.sin(theta0), -L * math.cos(theta0) }, angle = theta0 }
  world:add_revolute{ a = bob, anchor = { 0, 0 } }
end

function Exact(t)
  local theta = swing.at(t)
  return { bob = { position = { L * math.sin(theta), -L * math.cos(theta) }, angle = theta } }
end
