-- A car as a Box2D user builds it: a chassis and two wheels on wheel joints (a vertical
-- suspension spring with limits, the wheels free to turn), the rear wheel driven by the joint's
-- motor. It accelerates on flat ground, then drives over a bump. Rolling without slipping, its
-- speed is the wheel's spin relative to the chassis times the radius: v = |motor_speed| · r once
-- the motor has reached its speed (the traction it needs, m a, stays below μ m g while the motor's
-- torque limit keeps a ≤ τ / (r m)).
local check = require "check"

scene = { title = "Car on wheel joints", dt = 1/60, duration = 5, camera = { center = {12, 1}, height = 8 } }

local r, motor_speed, lower, upper = 0.4, -20, -0.25, 0.1
local bump_x = 25
local chassis, wheels, axles = nil, {}, {}
local cruise_speed, worst_travel_low, worst_travel_high, worst_off_axis = nil, 0, 0, 0
local travel = { low = math.huge, high = -math.huge }  -- the suspension's range, both wheels
local axle_x = { -1.1, 1.1 }

function PopulateWorld(world)
  -- Flat ground with a smooth bump 0.3 m high and 3 m long, listed right to left.
  local points = {}
  for x = 60, -5, -0.5 do
    local s = (x - bump_x) / 1.5
    points[#points + 1] = {x, math.abs(s) < 1 and 0.3 * (1 + math.cos(math.pi * s)) / 2 or 0}
  end
  world:add_chain{ points = points, friction = 0.9 }

  local y = r + 0.5
  chassis = world:add_box{ width = 3, height = 0.5, position = {0, y + 0.3}, mass = 200 }
  for i, dx in ipairs(axle_x) do
    wheels[i] = world:add_circle{ radius = r, position = {dx, r}, mass = 15, friction = 0.9 }
    axles[i] = world:add_wheel{ a = chassis, b = wheels[i], anchor = {dx, r}, axis = {0, 1}, spring_hertz = 4,
                                spring_damping = 0.7, lower = lower, upper = upper }
  end
  axles[1].motor_speed, axles[1].max_motor_torque = motor_speed, 400  -- rear-wheel drive
  scene.camera.follow = chassis  -- the sandbox's camera drives along
end

function OnStep(world, dt)
  for i, axle in ipairs(axles) do
    worst_travel_low = math.max(worst_travel_low, lower - axle.translation)
    worst_travel_high = math.max(worst_travel_high, axle.translation - upper)
    travel.low, travel.high = math.min(travel.low, axle.translation), math.max(travel.high, axle.translation)
    -- The wheel's centre in the chassis frame: on the axis x = axle_x[i].
    local local_wheel = (wheels[i].position - chassis.position):rotated(-chassis.angle)
    worst_off_axis = math.max(worst_off_axis, math.abs(local_wheel.x - axle_x[i]))
  end
  -- The speed just before the bump, on flat ground.
  if not cruise_speed and chassis.position.x > bump_x - 5 then
    cruise_speed = { v = chassis.velocity.x, spin = axles[1].speed, t = world.time }
  end
end

function Check(world)
  check.that("the car reached the bump", cruise_speed ~= nil)
  print(string.format("at t = %.2f s, x = %.1f: v = %.4f m/s, motor joint speed %.4f rad/s; after the bump x = %.1f",
                      cruise_speed.t, bump_x - 5, cruise_speed.v, cruise_speed.spin, chassis.position.x))
  print(string.format("suspension travel %.4f .. %.4f m, past its limits by %.4f m (low), %.4f m (high); wheels off their axes %.2g m",
                      travel.low, travel.high, worst_travel_low, worst_travel_high, worst_off_axis))
  -- Measured 0.0027 rad/s off: the contacts, solved after the motor, take a little of its speed back.
  check.near("the motor reached its speed", cruise_speed.spin, motor_speed, 0.01)
  check.near("speed = |motor_speed| · r (rolling without slipping)", cruise_speed.v, -motor_speed * r, 0.01 * -motor_speed * r)
  check.greater("the car crossed the bump", chassis.position.x, bump_x + 3)
  check.greater("the bump pushed a wheel up to its upper limit", travel.high, upper - 1e-3)
  check.less("suspension above its lower limit (within 5 mm)", worst_travel_low, 0.005)
  check.less("suspension below its upper limit (within 5 mm)", worst_travel_high, 0.005)
  check.less("the wheels stay on their axes", worst_off_axis, 1e-3)
end
