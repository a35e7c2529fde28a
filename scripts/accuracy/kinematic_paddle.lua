-- Balls struck by kinematic paddles moving at a constant velocity v_p: the impacts are located
-- inside the step against the paddle's own motion (x_p(t) = x_p0 + v_p t), as against a static
-- floor. The paddle's frame is inertial, so in it each ball is a ball bouncing on a static floor:
-- with the paddle's top at y_p(t) = v_py t and the ball's bottom h(t) = y − r − y_p(t) above it, a
-- flight from h_s with relative vertical velocity u_s = v_y − v_py lands after
--   s = (u_s + √(u_s² + 2 g h_s)) / g,
-- where the ball leaves with u' = −e u (Newton's law on the relative normal velocity: v_y' = v_py −
-- e (v_y − v_py)). Friction acts on the slip at the contact point, relative to the paddle,
-- σ = (v_x − v_px) + ω r: the impulse that stops it is P = −σ m_t, m_t = 1/(1/m + r²/I) = m/3 for a
-- disc; it sticks if |P| ≤ μ P_n (P_n = m (1 + e) |u|), else slides with P_t = −sign(σ) μ P_n;
-- then v_x += P_t/m, ω += r P_t / I (docs/design/thesis.md §8, impact_solve.cpp).
--   lane 1: e = 1, frictionless, v_p = (0, 2), dropped 1 m above the paddle: impacts at 0.2916 s
--           and 1.2826 s (relative speed 4.86 m/s)
--   lane 2: e = 0.5, frictionless, v_p = (0, 2), dropped 2.5 m above: impacts at 0.5387, 1.2813
--           and 1.6526 s (relative speeds 7.28, 3.64, 1.82 m/s; the next, 0.91 m/s, at 1.838 s)
--   lane 3: as lane 2 with μ = 0.02 and v_p = (1.5, 2): the paddle slides under the ball, every
--           impact slides (the friction needed to stop the slip is more than μ P_n)
-- All impact times are off every step grid of the sweep.
scene = { sleeping = false, title = "Balls struck by moving kinematic paddles, e = 1 and 0.5", dt = 1 / 60,
          duration = 1.8, camera = { center = {10, 3}, height = 10 } }

local g, m, r = 9.80665, 1.0, 0.5
local inertia = 0.5 * m * r * r
local threshold = 0.5  -- WorldDef::restitution_threshold [m/s]: every impact here is faster
local lanes = {
  { x = 0, e = 1, mu = 0, vp = {0, 2}, drop = 1.0 },
  { x = 10, e = 0.5, mu = 0, vp = {0, 2}, drop = 2.5 },
  { x = 20, e = 0.5, mu = 0.02, vp = {1.5, 2}, drop = 2.5 },
}

accuracy = {
  group = "impact",
  -- Located impacts against the paddle's straight line: RK4 integrates each parabola exactly and
  -- every impact is at its moment, so it is exact to round-off; the Euler family keeps order 1.
  expected_order = { rk4 = "exact" },
  t_end = 1.8,
  reference_length = 1,  -- absolute error [m]
  metrics = { "velocity" },
  reference_speed = 1,
  note = "impacts with kinematic paddles moving at 2 m/s (one sideways with friction), off the step grid",
}

function PopulateWorld(world)
  for i, lane in ipairs(lanes) do
    world:add_box{ name = "paddle" .. i, type = "kinematic", width = 8, height = 0.4, position = {lane.x, -0.2},
                   velocity = lane.vp, restitution = 0, friction = lane.mu, static_friction = lane.mu }
    world:add_circle{ name = "ball" .. i, radius = r, mass = m, position = {lane.x, r + lane.drop},
                      restitution = lane.e, friction = lane.mu, static_friction = lane.mu }
  end
end

-- The ball of `lane` at time t: position, velocity, by flights from impact to impact.
local function ball(lane, t)
  local ts, x, y, vx, vy, w = 0, lane.x, r + lane.drop, 0, 0, 0
  local vpx, vpy = lane.vp[1], lane.vp[2]
  while true do
    local h, u = y - r - vpy * ts, vy - vpy
    local s = (u + math.sqrt(u * u + 2 * g * h)) / g  -- the flight to the next impact
    if t <= ts + s then
      local d = t - ts
      return { x + vx * d, y + vy * d - 0.5 * g * d * d }, { vx, vy - g * d }
    end
    x, y, vx, vy, ts = x + vx * s, y + vy * s - 0.5 * g * s * s, vx, vy - g * s, ts + s
    local un = vy - vpy
    assert(-un > threshold, "an impact below the restitution threshold: not in this problem")
    local pn = m * (1 + lane.e) * -un
    vy = vpy - lane.e * un
    local slip = (vx - vpx) + w * r
    local pt = -slip / (1 / m + r * r / inertia)
    local limit = lane.mu * pn
    if math.abs(pt) > limit then pt = slip > 0 and -limit or limit end
    vx, w = vx + pt / m, w + r * pt / inertia
  end
end

function Exact(t)
  local out = {}
  for i, lane in ipairs(lanes) do
    local p, v = ball(lane, t)
    out["ball" .. i] = { position = p, velocity = v }
    out["paddle" .. i] = { position = { lane.x + lane.vp[1] * t, -0.2 + lane.vp[2] * t }, velocity = lane.vp }
  end
  return out
end
