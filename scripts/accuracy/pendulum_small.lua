-- The pendulum of pendulum_revolute.lua (a 1 kg disc of radius 0.1 m, 1 m from a pin to the world)
-- released from rest at θ0 = 0.2 rad: sin(θ/2) = k sn(K − ω0 t, k), k = sin(θ0/2), T = 4 K(k)/ω0
-- (scripts/elliptic.lua). Integrated with its joint, every integrator keeps its order.
local elliptic = require "elliptic"

local m, r, L, g, theta0 = 1.0, 0.1, 1.0, 9.81, 0.2
scene = { sleeping = false, title = "Pendulum on a revolute joint (θ0 = 0.2 rad)", gravity = { 0, -g }, dt = 1 / 60,
          duration = 2.1, camera = { center = {0, -0.3}, height = 3 } }

local w0 = math.sqrt(m * g * L / (0.5 * m * r * r + m * L * L))
local swing = elliptic.pendulum{ theta0 = theta0, omega0 = w0 }

accuracy = {
  group = "mechanism",
  t_end = 2.1,  -- one period and a little
  reference_length = L,
  metrics = { "energy" },
  period = swing.period,
  period_body = "bob",
  note = string.format("small amplitude: T = 4K(k)/ω0 = %.6f s, k = sin(θ0/2) = %.6f", swing.period, swing.k),
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
