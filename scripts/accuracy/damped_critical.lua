-- Critically damped spring–mass, F = −k x − c v (docs/design/accuracy.md §3.4), m = 1 kg, k = 4π² N/m, x0 = 0.1 m,
-- v0 = 0, c = 2 ζ √(k m) with ζ = 1, x(1) = 1.3600931466e−3.
--   ζ < 1: x = e^{−ζω₀t} [x0 cos ω_d t + ((v0 + ζω₀x0)/ω_d) sin ω_d t],  ω_d = ω₀ √(1 − ζ²)
--   ζ = 1: x = [x0 + (v0 + ω₀x0) t] e^{−ω₀t}
--   ζ > 1: x = A e^{r₁t} + B e^{r₂t},  r₁,₂ = −ω₀(ζ ∓ √(ζ² − 1)),  B = (v0 − r₁x0)/(r₂ − r₁),  A = x0 − B
-- The damping is the spring's own (along its axis), so an integrator that treats springs and
-- dampers implicitly treats this one so.
scene = { sleeping = false, title = "Spring–mass, critically damped (ζ = 1)", gravity = {0, 0}, dt = 1 / 60, duration = 2,
          camera = { center = {0, 0}, height = 0.5 } }

local m, k, x0, v0, zeta = 1.0, 4 * math.pi ^ 2, 0.1, 0.0, 1
local w0 = math.sqrt(k / m)
local c = 2 * zeta * math.sqrt(k * m)

accuracy = {
  group = "smooth",
  t_end = 2,
  reference_length = x0,  -- the initial displacement [m]
  metrics = { "velocity" },
  reference_speed = w0 * x0,
  note = "ζ = 1, x(1) = 1.3600931466e−3",
}

function PopulateWorld(world)
  local ball = world:add_circle{ name = "ball", radius = 0.02, mass = m, position = {x0, 0} }
  world:add_spring{ a = ball, anchor = {0, 0}, stiffness = k, rest_length = 0, damping = c }
end

-- Position and velocity along x at time t.
local function solution(t)
  if zeta < 1 then
    local wd = w0 * math.sqrt(1 - zeta * zeta)
    local e = math.exp(-zeta * w0 * t)
    local B = (v0 + zeta * w0 * x0) / wd
    local x = e * (x0 * math.cos(wd * t) + B * math.sin(wd * t))
    local v = -zeta * w0 * x + e * (-x0 * wd * math.sin(wd * t) + B * wd * math.cos(wd * t))
    return x, v
  elseif zeta == 1 then
    local e = math.exp(-w0 * t)
    local a = v0 + w0 * x0
    return (x0 + a * t) * e, (a - w0 * (x0 + a * t)) * e
  else
    local s = math.sqrt(zeta * zeta - 1)
    local r1, r2 = -w0 * (zeta - s), -w0 * (zeta + s)
    local B = (v0 - r1 * x0) / (r2 - r1)
    local A = x0 - B
    return A * math.exp(r1 * t) + B * math.exp(r2 * t), A * r1 * math.exp(r1 * t) + B * r2 * math.exp(r2 * t)
  end
end

function Exact(t)
  local x, v = solution(t)
  return { ball = { position = {x, 0}, velocity = {v, 0} } }
end
