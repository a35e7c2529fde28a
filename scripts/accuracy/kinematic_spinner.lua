-- Balls struck by kinematic bars spinning about their centres at ω = 2 rad/s, without gravity: the
-- bar's pose along the step is θ(t) = ω t (the kinematic body's constant angular velocity), and the
-- impact is located where the ball's straight flight meets the bar's turning top face. In the
-- bar's frame the ball's centre is at ℓ(t) = R(−ω t) c(t), and it touches the face when
--   f(t) = ℓ_y(t) − w − r = −sin(ω t) c_x(t) + cos(ω t) c_y(t) − w − r = 0
-- (w the bar's half thickness; |ℓ_x| < L, the face's half length, so the face and not a corner),
-- solved here by bisection to round-off. At the contact point p = c − r n, n = (−sin ωt, cos ωt),
-- the bar moves at v_k = ω × p = ω (−p_y, p_x), and the frictionless ball leaves with
--   v' = v − (1 + e) ((v − v_k) · n) n,
-- its spin untouched; then it flies straight, away from the bar (checked: no second contact).
--   lane 1: e = 1, ball r = 0.25 from (1.2, 2) at (0, −3) m/s onto a bar 4 m × 0.2 m: impact at
--           t = 0.2792 s, 1.63 m along the face, relative normal speed 5.8 m/s
--   lane 2: the same with e = 0.5
-- Straight flights and a bar that turns at a constant rate: every integrator is exact.
scene = { sleeping = false, title = "Balls struck by spinning kinematic bars, e = 1 and 0.5", gravity = {0, 0},
          dt = 1 / 60, duration = 1, camera = { center = {5, 1}, height = 8 } }

local r, halfl, halfw, omega = 0.25, 2.0, 0.1, 2.0
local start, velocity = {1.2, 2.0}, {0, -3.0}
local lanes = { { x = 0, e = 1 }, { x = 10, e = 0.5 } }

accuracy = {
  group = "impact",
  -- The bar's own motion is exact (θ += h ω); the ball's flights are straight lines, which every
  -- integrator follows exactly, and the impact is located against the turning face.
  expected_order = { euler = "exact", semi_implicit_euler = "exact", rk4 = "exact", implicit_euler = "exact" },
  t_end = 1,
  reference_length = 1,  -- absolute error [m]
  metrics = { "velocity" },
  reference_speed = 1,
  note = "frictionless impacts with bars turning at 2 rad/s, off the step grid",
}

function PopulateWorld(world)
  for i, lane in ipairs(lanes) do
    world:add_box{ name = "bar" .. i, type = "kinematic", width = 2 * halfl, height = 2 * halfw, position = {lane.x, 0},
                   angular_velocity = omega, restitution = 0, friction = 0 }
    world:add_circle{ name = "ball" .. i, radius = r, mass = 1, position = {lane.x + start[1], start[2]},
                      velocity = velocity, restitution = lane.e, friction = 0 }
  end
end

-- The gap of the ball's flight before the impact to the bar's top face, in the bar's frame.
local function face_gap(t)
  local cx, cy = start[1] + velocity[1] * t, start[2] + velocity[2] * t
  return -math.sin(omega * t) * cx + math.cos(omega * t) * cy - halfw - r
end

-- The impact: its time (bisection on [0, 0.5], where f goes from + to −), the contact point and
-- normal, relative to the bar's centre.
local impact = (function()
  local lo, hi = 0.0, 0.5
  assert(face_gap(lo) > 0 and face_gap(hi) < 0)
  for _ = 1, 200 do
    local mid = 0.5 * (lo + hi)
    if mid <= lo or mid >= hi then break end
    if face_gap(mid) > 0 then lo = mid else hi = mid end
  end
  local t = hi
  local n = { -math.sin(omega * t), math.cos(omega * t) }
  local c = { start[1] + velocity[1] * t, start[2] + velocity[2] * t }
  local along = math.cos(omega * t) * c[1] + math.sin(omega * t) * c[2]
  assert(math.abs(along) < halfl, "the ball must hit the face, not a corner")
  return { t = t, n = n, c = c, p = { c[1] - r * n[1], c[2] - r * n[2] } }
end)()

function Exact(t)
  local out = {}
  for i, lane in ipairs(lanes) do
    local p, v
    if t <= impact.t then
      v = velocity
      p = { lane.x + start[1] + v[1] * t, start[2] + v[2] * t }
    else
      local vk = { -omega * impact.p[2], omega * impact.p[1] }
      local vn = (velocity[1] - vk[1]) * impact.n[1] + (velocity[2] - vk[2]) * impact.n[2]
      v = { velocity[1] - (1 + lane.e) * vn * impact.n[1], velocity[2] - (1 + lane.e) * vn * impact.n[2] }
      local s = t - impact.t
      p = { lane.x + impact.c[1] + v[1] * s, impact.c[2] + v[2] * s }
    end
    out["ball" .. i] = { position = p, velocity = v }
    out["bar" .. i] = { position = { lane.x, 0 }, angle = omega * t }
  end
  return out
end
