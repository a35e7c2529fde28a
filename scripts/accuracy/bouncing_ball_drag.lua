-- Two balls dropped from h0 = 1 m onto a floor through air with linear drag F = −c v (c = 1.5 N·s/m on
-- 1 kg, τ = m/c), one elastic (e = 1), one with e = 0.8. With drag the flight is not a parabola, so
-- RK4 is not exact between the bounces and its order shows: each bounce is found on RK4's dense
-- output, integrated to and resolved at the moment of contact (impacts = "located"), so the error
-- stays O(h⁴) through every bounce, at impact phases that vary with dt. A flight that starts at
-- height y0 with vertical velocity v0 solves m y'' = −m g − c y', whose solution is
--   y(s) = y0 + τ (v0 + g τ)(1 − e^{−s/τ}) − g τ s,   v(s) = (v0 + g τ) e^{−s/τ} − g τ;
-- from its apex a flight falls H in the time x with g τ (x − τ (1 − e^{−x/τ})) = H, solved by Newton's
-- method from x0 = H/(g τ) + τ (the function is convex, so the iterates fall monotonically to the root).
scene = { sleeping = false, title = "Bouncing balls with air drag, e = 1 and 0.8", dt = 1 / 60, duration = 1.9,
          camera = { center = {0, 0.6}, height = 1.6 } }

local g, h0, r, c, m = 9.80665, 1.0, 0.1, 1.5, 1.0
local tau = m / c
local threshold = 0.5  -- WorldDef::restitution_threshold: slower impacts do not bounce
local balls = { { name = "elastic", e = 1.0, x = -1 }, { name = "damped", e = 0.8, x = 1 } }

accuracy = {
  group = "impact",
  -- The damped ball's seventh impact (t = 1.951 s, at 0.45 m/s, under the restitution threshold)
  -- ends its bouncing: from then on it rests on the floor, which is the contact solver's business,
  -- once per step (measured: the resting ball sinks 3e-4 m/s at dt = 1/60, 8e-5 m/s at 1/120,
  -- order 2, and that error would hide the impacts' order), so the problem ends before it.
  t_end = 1.9,
  reference_length = h0,
  metrics = { "velocity" },
  reference_speed = math.sqrt(2 * g * h0),
  note = "air drag c = 1.5 N·s/m on 1 kg; 3 and 6 bounces in 1.9 s, every one inside a step",
}

function PopulateWorld(world)
  world:add_box{ name = "floor", width = 6, height = 1, position = {0, -0.5}, static = true, friction = 0 }
  for _, b in ipairs(balls) do
    local ball = world:add_circle{ name = b.name, radius = r, mass = m, position = {b.x, r + h0}, restitution = b.e,
                                   friction = 0 }
    world:add_damper{ body = ball, coefficient = c }
  end
end

-- Time to fall H from rest with drag.
local function fallTime(H)
  local x = H / (g * tau) + tau
  for _ = 1, 100 do
    local f = g * tau * (x - tau * (1 - math.exp(-x / tau))) - H
    local df = g * (1 - math.exp(-x / tau))
    local step = f / df
    x = x - step
    if math.abs(step) <= 1e-16 * x then break end
  end
  return x
end

-- The flights of one ball: { start, y0, v0 } from its release, each bounce starting a new one.
local function flights(e, t_end)
  local list = { { start = 0, y0 = h0, v0 = 0 } }
  local start, apex_time, H = 0, 0, h0
  while true do
    local x = fallTime(H)
    local t_hit = start + apex_time + x
    if t_hit > t_end + 1 then break end
    local fl = list[#list]
    local s = t_hit - fl.start
    local v = (fl.v0 + g * tau) * math.exp(-s / tau) - g * tau  -- < 0
    local up = -v >= threshold and -e * v or 0
    list[#list + 1] = { start = t_hit, y0 = 0, v0 = up }
    if up == 0 then break end
    start = t_hit
    apex_time = tau * math.log(1 + up / (g * tau))
    H = tau * (up + g * tau) * (1 - math.exp(-apex_time / tau)) - g * tau * apex_time
  end
  return list
end

local paths = {}
for i, b in ipairs(balls) do paths[i] = flights(b.e, accuracy.t_end) end

function Exact(t)
  local out = {}
  for i, b in ipairs(balls) do
    local list = paths[i]
    local k = 1
    while k < #list and list[k + 1].start <= t do k = k + 1 end
    local fl = list[k]
    local y, v
    if fl.v0 == 0 and fl.y0 == 0 then
      y, v = 0, 0  -- at rest on the floor
    else
      local s = t - fl.start
      local E = math.exp(-s / tau)
      y = fl.y0 + tau * (fl.v0 + g * tau) * (1 - E) - g * tau * s
      v = (fl.v0 + g * tau) * E - g * tau
    end
    out[b.name] = { position = { b.x, r + y }, velocity = { 0, v } }
  end
  return out
end
