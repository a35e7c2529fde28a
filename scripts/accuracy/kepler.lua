-- Kepler orbit under a central force written in Lua (docs/design/accuracy.md §3.6): F = −GM m r/|r|³ toward a
-- fixed attractor at the origin. a = 1 m, e = 0.6, period P = 10 s, so GM = 4π²a³/P² =
-- 0.3947841760435743 m³/s²; r0 = (a(1 − e), 0) = (0.4, 0), v0 = (0, √(GM (1 + e)/(a (1 − e)))) =
-- (0, 2π/5). Exact positions from Kepler's equation E − e sin E = 2πt/P:
--   x = a (cos E − e),  y = a √(1 − e²) sin E;  r(10.1) = (0.38783655542130124, 0.12439662959647375)
-- Invariants: energy −GM m/(2a) = −0.19739208802178715 J, angular momentum m √(GM a (1 − e²)) =
-- 0.5026548245743668 kg·m²/s. The world does not know the potential of a Lua force, so the
-- `accuracy` table gives the energy.
scene = { sleeping = false, title = "Kepler orbit (Lua force)", gravity = {0, 0}, dt = 1 / 60, duration = 10,
          camera = { center = {-0.6, 0}, height = 2 } }

local a, e, P = 1.0, 0.6, 10.0
local GM = 4 * math.pi ^ 2 * a ^ 3 / P ^ 2
local b = a * math.sqrt(1 - e * e)
local n = 2 * math.pi / P  -- mean motion [rad/s]

accuracy = {
  group = "smooth",
  t_end = 10.1,
  reference_length = a,  -- the semi-major axis [m]
  metrics = { "energy", "angmom", "velocity" },
  reference_speed = 2 * math.pi * a / P,
  long_run = 1000,
  note = "4 Lua calls per step with RK4, 1 with the Euler variants",
  energy = function(bodies)
    local p = bodies.planet
    return 0.5 * p.mass * (p.vx * p.vx + p.vy * p.vy) - GM * p.mass / math.sqrt(p.x * p.x + p.y * p.y)
  end,
}

function PopulateWorld(world)
  local planet = world:add_circle{ name = "planet", radius = 0.02, mass = 1,
                                   position = { a * (1 - e), 0 },
                                   velocity = { 0, math.sqrt(GM * (1 + e) / (a * (1 - e))) } }
  world:add_force{ body = planet, evaluate = function(s)
    local x, y = s.center.x, s.center.y
    local r2 = x * x + y * y
    local f = -GM * s.mass / (r2 * math.sqrt(r2))
    return f * x, f * y
  end }
end

-- Eccentric anomaly E for time t: Newton's method on E − e sin E = n t (converges to round-off).
local function anomaly(t)
  local M = n * t
  local E = M + e * math.sin(M)
  for _ = 1, 50 do
    local d = (E - e * math.sin(E) - M) / (1 - e * math.cos(E))
    E = E - d
    if math.abs(d) < 1e-16 * math.max(1, math.abs(E)) then break end
  end
  return E
end

function Exact(t)
  local E = anomaly(t)
  local dE = n / (1 - e * math.cos(E))
  return { planet = {
    position = { a * (math.cos(E) - e), b * math.sin(E) },
    velocity = { -a * math.sin(E) * dE, b * math.cos(E) * dE },
  } }
end
