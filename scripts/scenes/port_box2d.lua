-- A Box2D v3 program ported to rigidlab (docs/porting.md, "A worked port from Box2D v3"): crates
-- dropped on a conveyor belt (a surface material's tangent speed), a ball slowed by rolling
-- resistance, a pendulum hinged by local anchors (localAnchorA on the ground, localAnchorB on the
-- bar) and a spinner turned by a torque. Check, against closed forms: the crates move with the belt,
-- the ball has lost ⅔ c g t of its speed, the pendulum's anchor stays on the hinge, and the spinner
-- turns at τ t / I.
local check = require "check"

scene = { title = "Port from Box2D v3: conveyor, rolling resistance, local anchors", gravity = {0, -10}, duration = 2 }

local crates, ball, pendulum, spinner = {}, nil, nil, nil

function PopulateWorld(world)
  -- b2MakeOffsetBox(10, 0.25, {0, 0}) on the ground body, friction 0.8, tangentSpeed 2.
  world:add_box{ static = true, width = 20, height = 0.5, friction = 0.8, tangent_speed = 2 }
  for i = 1, 3 do
    crates[i] = world:add_box{ width = 1, height = 1, position = {-6 + 2 * i, 1}, friction = 0.8 }
  end
  -- A second floor for the ball: rollingResistance 0.1 on the ball's material.
  world:add_box{ static = true, width = 40, height = 0.5, position = {0, -10} }
  ball = world:add_circle{ radius = 0.5, position = {-15, -9.25}, velocity = {4, 0}, angular_velocity = -8,
                           rolling_resistance = 0.1 }
  -- b2RevoluteJointDef: bodyIdA the ground (localAnchorA {-8, 6}, a world point), bodyIdB the bar
  -- (localAnchorB {0, 1}). rigidlab's a is the dynamic body and b, omitted, the world.
  pendulum = world:add_box{ width = 0.2, height = 2, position = {-7, 6}, angle = math.pi / 2 }
  world:add_revolute{ a = pendulum, local_anchor_a = {0, 1}, local_anchor_b = {-8, 6} }
  -- b2Body_ApplyTorque every step for a second: apply_torque's duration.
  spinner = world:add_box{ width = 1, height = 1, position = {10, 8}, mass = 6, gravity_scale = 0 }
  spinner:apply_torque(5, 1)
end

function Check(world)
  for i, crate in ipairs(crates) do check.near("crate " .. i .. " moves with the belt", crate.velocity.x, 2, 1e-3) end
  check.near("the ball slowed by 2/3 c g t", ball.velocity.x, 4 - 2 / 3 * 0.1 * 10 * 2, 0.05)
  check.near("the pendulum hangs from its hinge", (pendulum:world_point({0, 1}) - vec2(-8, 6)):length(), 0, 1e-3)
  -- A 1 m cube of 6 kg: I = 6 · 2 / 12 = 1 kg·m²; 5 N·m for 1 s.
  check.near("the spinner turns at tau t / I", spinner.angular_velocity, 5, 1e-9)
end
