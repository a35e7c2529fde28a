-- A parallelogram four-bar linkage: two equal rods (crank and rocker, 1 m × 0.05 m, 1 kg) hang
-- from pins to the world 1 m apart, and a coupler rod (1 m × 0.05 m, 1 kg) joins their lower ends:
-- a closed loop of four pins. Released at rest with the cranks at φ0 = 1 rad, the coupler moves in
-- pure translation, every point of it on a circle of the crank's radius, and the linkage is a
-- pendulum in φ: (2 I_p + m_c L²) φ'' = −g L (m_r + m_c) sin φ, I_p = m_r (L² + w²)/12 + m_r (L/2)²
-- the rod's inertia about its pin, so sin(φ/2) = k sn(K − ω0 t, k) with k = sin(φ0/2)
-- (scripts/elliptic.lua). Its three bodies touch nothing: the loop is integrated with its joints.
local elliptic = require "elliptic"

local m_r, m_c, L, w, g, phi0 = 1.0, 1.0, 1.0, 0.05, 9.81, 1.0
scene = { sleeping = false, title = "Parallelogram four-bar linkage", gravity = { 0, -g }, dt = 1 / 60,
          duration = 3, camera = { center = {0, -0.7}, height = 3 } }

local I_p = m_r * (L * L + w * w) / 12 + m_r * (L / 2) ^ 2
local w0 = math.sqrt(g * L * (m_r + m_c) / (2 * I_p + m_c * L * L))
local swing = elliptic.pendulum{ theta0 = phi0, omega0 = w0 }

accuracy = {
  group = "mechanism",
  t_end = 3,
  reference_length = L,
  metrics = { "energy" },
  period = swing.period,
  period_body = "crank",
  note = string.format("ω0 = %.6f rad/s, T = %.6f s", w0, swing.period),
}

local pivots = { crank = -0.5, rocker = 0.5 }

-- Each body at crank angle φ: the rods turn about their pins, the coupler translates.
local function pose(phi)
  local s, c = math.sin(phi), math.cos(phi)
  local out = {}
  for name, x in pairs(pivots) do
    out[name] = { position = { x + 0.5 * L * s, -0.5 * L * c }, angle = phi }
  end
  out.coupler = { position = { L * s, -L * c }, angle = 0 }
  return out
end

function PopulateWorld(world)
  local at = pose(phi0)
  local bodies = {}
  for name in pairs(pivots) do
    bodies[name] = world:add_box{ name = name, width = w, height = L, mass = m_r, position = at[name].position,
                                  angle = phi0 }
  end
  local coupler = world:add_box{ name = "coupler", width = L, height = w, mass = m_c, position = at.coupler.position }
  for name, x in pairs(pivots) do
    world:add_revolute{ a = bodies[name], anchor = { x, 0 } }
    world:add_revolute{ a = bodies[name], b = coupler, anchor = { x + L * math.sin(phi0), -L * math.cos(phi0) } }
  end
end

function Exact(t) return pose((swing.at(t))) end
