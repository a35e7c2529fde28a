-- A LÖVE physics program ported to rigidlab (docs/porting.md, "A worked port from LÖVE"): a ball
-- dropped on the ground bounces with restitution 0.6, a wheel pinned to the world turns on its
-- motor, the arrow keys push the ball, and a contact callback counts the ball's bounces by the
-- shapes' user data. Check: the first bounce rises to e² of the drop height (0.36 · 4 m) and the
-- wheel turns at its motor's speed.
local check = require "check"

scene = { title = "Port from LÖVE: a bouncing ball and a motor", gravity = {0, -9.81}, duration = 3 }

local ball, wheel
local bounces, apex, rising = 0, 0, false

function PopulateWorld(world)
  local ground = world:add_box{ static = true, width = 12.5, height = 0.625, position = {0, -0.3125} }
  ground.shapes[1].user_data = "ground"
  ball = world:add_circle{ radius = 0.3125, position = {0, 4.3125}, restitution = 0.6, contact_events = true }
  ball.shapes[1].user_data = "ball"
  wheel = world:add_box{ width = 1.5, height = 0.2, position = {4, 3} }
  world:add_revolute{ a = wheel, anchor = {4, 3}, motor_speed = 2, max_motor_torque = 100 }
end

function OnContactBegin(world, contact)
  if contact.shape_a.user_data == "ball" or contact.shape_b.user_data == "ball" then bounces = bounces + 1 end
end

function OnKey(world, key)
  if key == "right" then ball:apply_force({25, 0}) end
  if key == "up" then ball:apply_impulse({0, 1.5}) end
end

function OnStep(world, dt)
  -- The top of the first bounce: the ball's height when it stops rising after the first contact.
  if bounces == 1 and ball.velocity.y > 0 then rising = true end
  if rising and bounces == 1 then apex = math.max(apex, ball.position.y - 0.3125) end
end

function Check(world)
  check.that("the ball bounced", bounces >= 2, tostring(bounces))
  check.near("the first bounce rises to e^2 of the drop", apex, 0.36 * 4, 0.03)
  check.near("the wheel turns at its motor's speed", wheel.angular_velocity, 2, 1e-6)
end
