-- Motorised revolute joints. A balanced four-bladed windmill on a motor pin: the motor applies at
-- most max_motor_torque, so the rotor spins up at α = τ / I (its speed grows by τ h / I per step)
-- until it reaches motor_speed, which it then keeps. Two cranks, an arm with a weight, on motors
-- whose max_motor_torque τ is below the weight's largest torque m g r: they stall, short of
-- motor_speed. One is placed at rest where gravity's torque m g r sin φ (φ from hanging down)
-- equals τ, sin φ = τ / (m g r), and stays there. The other starts hanging down and swings up: the
-- motor's work τ φ against the weight's m g r (1 − cos φ) stops it at the root φ_max of
-- τ φ = m g r (1 − cos φ), past which it never gets; then it falls back.
-- (No damping settles them here. Damping once scaled the step's gravity too, v ← (v + h g) / (1 + h c),
-- so a damped crank held by its motor stalled where m g r sin φ = τ (1 + h c); it now damps the
-- velocity the step starts with (v ← v / (1 + h c) + h g): with linear and angular damping 6 on the
-- swung crank, measured 0.5339 rad after 8 s at h = 1/240 against sin φ = τ / (m g r): 0.5352 rad
-- (0.5485 before the fix, = asin(1.025 τ / (m g r))).)
local check = require "check"

scene = { title = "Windmill and stalled cranks", dt = 1/240, duration = 2.5, camera = { center = {3, 2}, height = 7 } }

local motor_speed, rotor_torque = 3, 40
local crank_r, crank_mass, crank_torque = 1.0, 4, 20   -- m g r = 39.2 N·m > 20 N·m
local rotor, rotor_pin, held, held_pin, swung, swung_pin
local spin_up, stall, held_drift, swing_max, fastest, torque_error = {}, nil, 0, 0, 0, 0

-- A crank pinned at `pivot`, turned by `angle` from hanging down, its motor short of torque.
local function crank(world, pivot, angle)
  local body = world:add_body{ position = pivot, angle = angle }
  body:add_shape{ shape = "box", width = 0.05, height = crank_r, offset = {0, -crank_r / 2}, density = 1e-3, mask = 0 }
  body:add_shape{ shape = "circle", radius = 0.15, offset = {0, -crank_r}, mask = 0 }
  body.mass = crank_mass
  return body, world:add_revolute{ a = body, anchor = pivot, motor_speed = motor_speed, max_motor_torque = crank_torque }
end

-- The weight's torque arm: its centre of mass is r_c from the pin.
local function arm(body) return (body.center - body.position):length() end

function PopulateWorld(world)
  world:add_box{ width = 0.3, height = 3, position = {0, 1.5}, static = true }  -- the tower, behind the rotor
  rotor = world:add_body{ position = {0, 3} }
  for k = 0, 3 do
    rotor:add_shape{ shape = "box", width = 2, height = 0.2, offset = vec2(1.1, 0):rotated(k * math.pi / 2),
                     angle = k * math.pi / 2, density = 5, mask = 0 }
  end
  rotor_pin = world:add_revolute{ a = rotor, anchor = {0, 3}, motor_speed = motor_speed, max_motor_torque = rotor_torque }

  swung, swung_pin = crank(world, vec2(6, 3), 0)
  local g = -world.gravity.y
  stall = math.asin(crank_torque / (crank_mass * g * arm(swung)))
  held, held_pin = crank(world, vec2(3.5, 3), stall)
end

function OnStep(world, dt)
  if world.step_count == 30 then spin_up.omega, spin_up.steps = rotor.angular_velocity, world.step_count end
  held_drift = math.max(held_drift, math.abs(held.angle - stall))
  swing_max = math.max(swing_max, swung.angle)
  fastest = math.max(fastest, swung.angular_velocity)
  torque_error = math.max(torque_error, math.abs(held_pin.reaction_torque - crank_torque),
                          math.abs(swung_pin.reaction_torque - crank_torque))
end

-- The root of τ φ = m g r (1 − cos φ) in (0, π), by bisection (the left side is above the right
-- until φ_max).
local function swing_root(g, r)
  local lo, hi = 1e-6, math.pi
  for _ = 1, 100 do
    local mid = (lo + hi) / 2
    if crank_torque * mid > crank_mass * g * r * (1 - math.cos(mid)) then lo = mid else hi = mid end
  end
  return lo
end

function Check(world)
  local g, h = -world.gravity.y, world.dt
  local phi_max = swing_root(g, arm(swung))
  print(string.format("rotor: ω after %d steps %.9f (τ n h / I = %.9f), now %.9f rad/s", spin_up.steps, spin_up.omega,
                      rotor_torque * spin_up.steps * h / rotor.inertia, rotor.angular_velocity))
  print(string.format("held crank off its stall angle %.3g rad; swung crank rose to %.5f rad (τ φ = m g r (1 − cos φ): %.5f), fastest %.4f rad/s, now %.4f rad",
                      held_drift, swing_max, phi_max, fastest, swung.angle))
  check.near("spin-up at τ / I", spin_up.omega, rotor_torque * spin_up.steps * h / rotor.inertia, 1e-9)
  check.near("the rotor reaches motor_speed", rotor.angular_velocity, motor_speed, 1e-6)
  check.near("and the joint reads it", rotor_pin.speed, motor_speed, 1e-6)
  check.less("a crank at sin φ = τ / (m g r) stays stalled there", held_drift, 1e-9)
  check.less("the stalled motors give their whole torque", torque_error, 1e-9)
  -- The pin is integrated with the crank (exact joints): measured 2.3e-8 of φ_max short, the peak
  -- falling between two steps. The contact solvers' pin took a little energy each step instead,
  -- in proportion to h (exact_joints = false: 0.66 % short at 1/240, 2.6 % at 1/60).
  check.near("the swing stops at τ φ = m g r (1 − cos φ)", swing_max, phi_max, 1e-6 * phi_max)
  check.less("the swinging crank never reaches motor_speed", fastest, motor_speed)
  check.less("and falls back", swung.angle, stall)
end
