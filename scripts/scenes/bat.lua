-- A ball dropped onto a kinematic bat spinning at ω = 6 rad/s about its centre: the impact is
-- located inside the step against the bat's turning face (the bat's angle is ω t within the step,
-- its velocity constant), and the ball leaves from the bat's moving surface. In the bat's frame
-- the ball's centre c(t) = (x0, y0 − g t²/2) touches the top face when
--   f(t) = −sin(ω t) c_x + cos(ω t) c_y − w − r = 0     (w: the bat's half thickness)
-- (here at t = 0.1439 s, 0.79 m from the axis: the face, not its end). At the contact point
-- p = c − r n, n = (−sin ω t, cos ω t), the bat moves at v_k = ω (−p_y, p_x); the ball's closing
-- speed is u = −(v − v_k)·n, its impulse (1 + e) m u, and it leaves with v' = v + (1 + e) u n
-- (frictionless), then flies a parabola. Checked against that closed form to 1e-9 with the
-- scene's step (RK4, dt = 1/60, the impact 0.63 of the way into its step; measured: exact to the
-- printed 12 digits). Before kinematic bodies were in the impact search the contact was solved
-- at the end of the step, and the ball ended 0.33 m off.
local check = require "check"

scene = { title = "Bat: a ball struck by a spinning kinematic bat", dt = 1 / 60, duration = 1, sleeping = false,
          camera = { center = {0, 1}, height = 6 } }

local g, m, r, e = 9.80665, 0.2, 0.1, 0.8
local half_length, half_width, omega = 1.0, 0.05, 6.0
local x0, y0 = 0.4, 0.8
local hits = {}

function PopulateWorld(world)
  world:add_box{ name = "bat", type = "kinematic", width = 2 * half_length, height = 2 * half_width,
                 angular_velocity = omega, restitution = 0, friction = 0 }
  world:add_circle{ name = "ball", radius = r, mass = m, position = {x0, y0}, restitution = e, friction = 0,
                    hit_events = true, hit_speed = 0 }
end

function OnHit(world, contact)
  hits[#hits + 1] = { speed = contact.approach_speed, impulse = contact.normal_impulse, time = world.time }
end

-- The closed form: the impact (bisection on f to round-off), then the parabola.
local function face_gap(t)
  return -math.sin(omega * t) * x0 + math.cos(omega * t) * (y0 - 0.5 * g * t * t) - half_width - r
end

local impact = (function()
  local lo, hi = 0.0, 0.5
  for _ = 1, 200 do
    local mid = 0.5 * (lo + hi)
    if mid <= lo or mid >= hi then break end
    if face_gap(mid) > 0 then lo = mid else hi = mid end
  end
  local t = hi
  local n = { -math.sin(omega * t), math.cos(omega * t) }
  local c = { x0, y0 - 0.5 * g * t * t }
  local p = { c[1] - r * n[1], c[2] - r * n[2] }
  local v = { 0, -g * t }
  local vk = { -omega * p[2], omega * p[1] }
  local u = -((v[1] - vk[1]) * n[1] + (v[2] - vk[2]) * n[2])
  return { t = t, c = c, u = u, along = math.cos(omega * t) * c[1] + math.sin(omega * t) * c[2],
           v = { v[1] + (1 + e) * u * n[1], v[2] + (1 + e) * u * n[2] } }
end)()

local function ball_at(t)
  local s = t - impact.t
  return { impact.c[1] + impact.v[1] * s, impact.c[2] + impact.v[2] * s - 0.5 * g * s * s },
         { impact.v[1], impact.v[2] - g * s }
end

function Check(world)
  local ball, bat = world:find("ball"), world:find("bat")
  local p, v = ball_at(world.time)
  print(string.format("impact at t = %.10f s, %.3f m along the bat, closing speed %.10f m/s; ball leaves at (%.6f, %.6f) m/s",
                      impact.t, impact.along, impact.u, impact.v[1], impact.v[2]))
  print(string.format("ball at t = %.3f s: (%.12f, %.12f), closed form (%.12f, %.12f)", world.time, ball.position.x,
                      ball.position.y, p[1], p[2]))
  check.less("the impact is on the bat's face", math.abs(impact.along), half_length - r)
  check.near("one hit", #hits, 1, 0)
  check.near("closing speed at the impact", hits[1].speed, impact.u, 1e-9)
  check.near("impulse (1 + e) m u", hits[1].impulse, (1 + e) * m * impact.u, 1e-9)
  check.near("ball x", ball.position.x, p[1], 1e-9)
  check.near("ball y", ball.position.y, p[2], 1e-9)
  check.near("ball vx", ball.velocity.x, v[1], 1e-9)
  check.near("ball vy", ball.velocity.y, v[2], 1e-9)
  check.near("the bat turned at its own rate", bat.angle, omega * world.time, 1e-12)
end
