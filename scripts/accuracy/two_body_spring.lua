-- Two bodies joined by a spring, both free (docs/design/accuracy.md §3.5): m1 = 1 kg at x = 0, m2 = 3 kg at
-- x = 1.2 m, k = 100 N/m, rest length 1 m, at rest. Reduced mass μ = 0.75 kg, ω = √(k/μ) =
-- 11.5470053838 rad/s. The separation is s(t) = 1 + 0.2 cos ωt about the fixed centre of mass
-- x_cm = 0.9 m: x1 = x_cm − (m2/M) s, x2 = x_cm + (m1/M) s; x1(1) = 0.0714139893, x2(1) = 1.1761953369.
-- Energy 2 J; the pair forces cancel, so total momentum stays 0 with every integrator.
scene = { sleeping = false, title = "Two-body spring", gravity = {0, 0}, dt = 1 / 60, duration = 5,
          camera = { center = {0.6, 0}, height = 2 } }

local m1, m2, k, L0, s0 = 1.0, 3.0, 100.0, 1.0, 1.2
local M = m1 + m2
local w = math.sqrt(k / (m1 * m2 / M))
local x_cm = m2 * s0 / M

accuracy = {
  group = "smooth",
  t_end = 5,
  reference_length = s0 - L0,  -- the stretch [m]
  metrics = { "energy", "momentum", "velocity" },
  reference_speed = w * (s0 - L0),
  note = "pair forces cancel: momentum exact for every integrator",
}

function PopulateWorld(world)
  local a = world:add_circle{ name = "m1", radius = 0.05, mass = m1, position = {0, 0} }
  local b = world:add_circle{ name = "m2", radius = 0.05, mass = m2, position = {s0, 0} }
  world:add_spring{ a = a, b = b, stiffness = k, rest_length = L0 }
end

function Exact(t)
  local s = L0 + (s0 - L0) * math.cos(w * t)
  local ds = -(s0 - L0) * w * math.sin(w * t)
  return {
    m1 = { position = { x_cm - (m2 / M) * s, 0 }, velocity = { -(m2 / M) * ds, 0 } },
    m2 = { position = { x_cm + (m1 / M) * s, 0 }, velocity = { (m1 / M) * ds, 0 } },
  }
end
