-- Joints through the Lua API: every kind made from Lua and checked after a few steps against what
-- it must keep (a pin's gap, a motor's speed, a limit, a rope's length, a gear's ratio, a pulley's
-- rope), every option read back, writes that enable what they set, breaking, removal, the lists,
-- and the messages of the mistakes a scene can make.
local check = require "check"

scene = { title = "Lua API: joints", duration = 2, gravity = {0, -10} }

local function refused(name, text, f, ...)
  local ok, message = pcall(f, ...)
  check.that(name .. " is refused", not ok, "no error")
  check.that(name .. ": message", message:find(text, 1, true) ~= nil, message)
end

local j = {}     -- joints by name
local b = {}     -- bodies by name
local worst = { pin = 0, gear = 0, pulley = 0, rigid = 0 }
local rope_length0, pulley_length0

function PopulateWorld(world)
  -- A pendulum pinned to the world (b omitted): its angle and speed are the body's own.
  b.pendulum = world:add_box{ width = 2, height = 0.1, position = {1, 20}, mass = 1 }
  j.pin = world:add_revolute{ a = b.pendulum, anchor = {0, 20}, name = "pin" }
  check.that("kind", j.pin.kind == "revolute" and j.pin.a == b.pendulum and j.pin.b == nil)
  check.that("defaults", not j.pin.enable_limit and not j.pin.enable_motor and not j.pin.enable_spring and
                         not j.pin.collide_connected and j.pin.break_force == math.huge and j.pin.name == "pin")

  -- A wheel driven at 2 rad/s: it turns counter-clockwise at +2 rad/s.
  b.wheel = world:add_circle{ radius = 0.5, position = {10, 20}, angular_damping = 0.5 }
  j.motor = world:add_revolute{ a = b.wheel, anchor = {10, 20}, motor_speed = 2, max_motor_torque = 100 }
  check.that("motor_speed enables the motor", j.motor.enable_motor and j.motor.motor_speed == 2 and j.motor.max_motor_torque == 100)

  -- An arm that falls onto its lower limit.
  b.arm = world:add_box{ width = 2, height = 0.2, position = {21, 20}, mass = 5 }
  j.limit = world:add_revolute{ a = b.arm, anchor = {20, 20}, lower_angle = -0.5, upper_angle = 0.5, spring_hertz = 0,
                                collide_connected = true, break_torque = 1e6 }
  check.that("limits enable the limit", j.limit.enable_limit and j.limit.lower_angle == -0.5 and j.limit.upper_angle == 0.5)
  check.that("spring_hertz 0 is no spring", not j.limit.enable_spring and j.limit.collide_connected and j.limit.break_torque == 1e6)

  -- A slider down a slope onto its upper limit, and one driven by its motor across gravity.
  b.slider = world:add_box{ width = 0.5, height = 0.5, position = {30, 20} }
  j.slide = world:add_prismatic{ a = b.slider, anchor = {30, 20}, axis = {1, -1}, lower = -1, upper = 1 }
  b.driven = world:add_box{ width = 0.5, height = 0.5, position = {40, 20} }
  j.drive = world:add_prismatic{ a = b.driven, anchor = {40, 20}, axis = {1, 0}, motor_speed = 0.5, max_motor_force = 1000 }
  check.that("prismatic motor", j.drive.enable_motor and j.drive.max_motor_force == 1000 and not j.drive.enable_limit)

  -- A rope (max_length alone) from a world point, and a rigid rod of the distance at creation.
  b.weight = world:add_box{ width = 0.2, height = 0.2, position = {51, 20} }
  j.rope = world:add_distance{ a = b.weight, anchor_b = {50, 20}, max_length = 2 }
  check.that("max_length enables the limit", j.rope.enable_limit and j.rope.max_length == 2 and j.rope.min_length == 0)
  check.near("length defaults to the distance now", j.rope.length, 1, 1e-12)
  b.bob = world:add_circle{ radius = 0.1, position = {62, 20} }
  j.rod = world:add_distance{ a = b.bob, anchor_b = {60, 20}, spring_damping = 0.5, max_spring_force = 10 }
  check.that("a rod", not j.rod.enable_limit and not j.rod.enable_spring and j.rod.max_spring_force == 10)
  check.that("anchors", j.rod.anchor_a == vec2(62, 20) and j.rod.anchor_b == vec2(60, 20))

  -- A hammer: head welded to a handle, spun; the weld keeps the shape.
  b.handle = world:add_box{ width = 0.1, height = 1, position = {70, 20}, mass = 0.5, angular_velocity = 5, gravity_scale = 0 }
  b.head = world:add_box{ width = 0.6, height = 0.2, position = {70, 20.6}, mass = 3, angular_velocity = 5, gravity_scale = 0 }
  j.weld = world:add_weld{ a = b.handle, b = b.head, anchor = {70, 20.5}, linear_hertz = 0, angular_damping = 0.1 }
  check.that("weld", j.weld.a == b.handle and j.weld.b == b.head and j.weld.linear_hertz == 0 and j.weld.angular_damping == 0.1)

  -- A wheel on a suspension spring (world axis up): it sags by g / ω².
  b.tyre = world:add_circle{ radius = 0.4, position = {80, 20} }
  j.wheel = world:add_wheel{ a = b.tyre, anchor = {80, 20}, axis = {0, 1}, spring_hertz = 2, spring_damping = 1 }
  check.that("spring_hertz enables the spring", j.wheel.enable_spring and j.wheel.spring_hertz == 2)

  -- A motor joint pulling a body to a world target, and a friction joint braking one.
  b.puck = world:add_circle{ radius = 0.3, position = {90, 20}, gravity_scale = 0 }
  j.drag = world:add_motor_joint{ a = b.puck, linear_offset = {92, 21}, angular_offset = 1, max_force = 1000, max_torque = 1000,
                                  motor_hertz = 5 }
  check.that("motor joint", j.drag.kind == "motor" and j.drag.linear_offset == vec2(92, 21) and j.drag.angular_offset == 1 and
                              j.drag.motor_hertz == 5 and j.drag.motor_damping == 1)
  b.sled = world:add_box{ width = 1, height = 1, position = {100, 20}, mass = 2, gravity_scale = 0, velocity = {3, 0} }
  j.brake = world:add_friction_joint{ a = b.sled, max_force = 4, max_torque = 1 }
  check.that("friction joint", j.brake.kind == "friction" and j.brake.max_force == 4 and j.brake.max_torque == 1)

  -- A pulley: the heavier side goes down, the rope keeps its length.
  b.left = world:add_box{ width = 0.5, height = 0.5, position = {108, 20}, mass = 2 }
  b.right = world:add_box{ width = 0.5, height = 0.5, position = {112, 20}, mass = 1 }
  j.pulley = world:add_pulley{ a = b.left, b = b.right, anchor_a = {108, 20.25}, anchor_b = {112, 20.25},
                               ground_a = {108, 24}, ground_b = {112, 24}, ratio = 1 }
  pulley_length0 = 3.75 + 3.75
  check.that("pulley", j.pulley.ground_a == vec2(108, 24) and j.pulley.ratio == 1)

  -- A gear train: two wheels pinned to the world, geared 2:1.
  b.big = world:add_circle{ radius = 1, position = {120, 20}, gravity_scale = 0, angular_velocity = 3 }
  b.small = world:add_circle{ radius = 0.5, position = {121.5, 20}, gravity_scale = 0 }
  j.axle_big = world:add_revolute{ a = b.big, anchor = {120, 20} }
  j.axle_small = world:add_revolute{ a = b.small, anchor = {121.5, 20} }
  j.gear = world:add_gear{ joint_a = j.axle_big, joint_b = j.axle_small, ratio = 2, name = "gear" }
  check.that("gear", j.gear.joint_a == j.axle_big and j.gear.joint_b == j.axle_small and j.gear.ratio == 2)

  -- A shelf on a weld that breaks under a blow (OnStep).
  b.shelf = world:add_box{ width = 1, height = 0.1, position = {130.5, 20} }
  j.bracket = world:add_weld{ a = b.shelf, anchor = {130, 20}, break_force = 20, name = "bracket" }

  -- Lists, lookups, handles.
  check.near("world:joints()", #world:joints(), 16, 0)
  check.that("find_joint", world:find_joint("pin") == j.pin and rawequal(world:find_joint("pin"), j.pin))
  check.that("find_joint of a missing name", world:find_joint("nothing") == nil)
  check.that("body:joints()", #b.big:joints() == 2 and #b.pendulum:joints() == 1 and b.pendulum:joints()[1] == j.pin)
  check.that("tostring", tostring(j.pin) == "revolute joint 'pin'" and tostring(j.wheel) == "wheel joint")

  -- Writes enable what they set, and read back.
  local t = world:add_revolute{ a = world:add_circle{ radius = 0.2, position = {140, 20} }, anchor = {140, 20} }
  t.motor_speed = 1
  check.that("writing motor_speed enables the motor", t.enable_motor and t.motor_speed == 1)
  t.enable_motor = false
  check.that("enable_motor written", not t.enable_motor)
  t.spring_hertz, t.spring_damping = 3, 0.7
  check.that("spring written", t.enable_spring and t.spring_hertz == 3 and t.spring_damping == 0.7)
  t.spring_hertz = 0
  check.that("spring_hertz 0 disables it", not t.enable_spring)
  t:set_limits(0.5, 1.5)  -- past the current upper bound 0: both at once
  check.that("set_limits", t.enable_limit and t.lower_angle == 0.5 and t.upper_angle == 1.5)
  t.name, t.break_force, t.collide_connected = "spare", 5, true
  check.that("common fields written", t.name == "spare" and t.break_force == 5 and t.collide_connected)
  t:remove()
  check.that("removed", t.removed and not t.broken and #world:joints() == 16)
  t:remove()  -- again: nothing
  refused("a removed joint's fields", "joint.angle: the revolute joint was removed", function() return t.angle end)
  local spare = world:add_distance{ a = b.bob, anchor_b = {60, 25}, min_length = 1, spring_hertz = 1 }
  world:remove(spare)
  check.that("world:remove(joint)", spare.removed)
  refused("world:remove of a removed joint", "remove: the distance joint was removed", world.remove, world, spare)

  -- Mistakes.
  local wall = world:add_box{ width = 1, height = 1, position = {150, 20}, static = true, name = "wall" }
  local floor = world:add_box{ width = 1, height = 1, position = {152, 20}, static = true }
  refused("both static", "add_weld: a and b are both static or kinematic (a: body 'wall' (id 19), static; b: body (id 20), static): at least one of the joint's bodies must be dynamic",
          world.add_weld, world, { a = wall, b = floor, anchor = {151, 20} })
  refused("pinned static", "add_revolute: a and b are both static or kinematic (a: body 'wall' (id 19), static; b: the world)",
          world.add_revolute, world, { a = wall, anchor = {150, 20} })
  refused("a zero axis", "add_prismatic: axis must not be zero, got (0, 0)",
          world.add_prismatic, world, { a = b.slider, anchor = {0, 0}, axis = {0, 0} })
  refused("lower > upper", "add_revolute: lower_angle (1) must not exceed upper_angle (-1)",
          world.add_revolute, world, { a = b.wheel, anchor = {0, 0}, lower_angle = 1, upper_angle = -1 })
  refused("prismatic lower > upper", "add_wheel: lower (2) must not exceed upper (1)",
          world.add_wheel, world, { a = b.wheel, anchor = {0, 0}, axis = {0, 1}, lower = 2, upper = 1 })
  refused("min_length > max_length", "add_distance: min_length (3) must not exceed max_length (2)",
          world.add_distance, world, { a = b.bob, anchor_b = {0, 0}, min_length = 3, max_length = 2 })
  refused("one bound", "add_revolute: upper_angle is required with lower_angle (an angle limit has two bounds)",
          world.add_revolute, world, { a = b.wheel, anchor = {0, 0}, lower_angle = -1 })
  refused("a motor without torque", "add_revolute: max_motor_torque is required with motor_speed (without it the motor has no torque)",
          world.add_revolute, world, { a = b.wheel, anchor = {0, 0}, motor_speed = 1 })
  refused("a gear of a distance joint", "add_gear: joint_b must be a revolute or prismatic joint, got a distance joint",
          world.add_gear, world, { joint_a = j.pin, joint_b = j.rope })
  refused("a gear of a non-joint", "add_gear: joint_a must be a joint (from world:add_revolute or add_prismatic), got 5",
          world.add_gear, world, { joint_a = 5, joint_b = j.pin })
  refused("a gear of ratio 0", "add_gear: ratio must not be 0", world.add_gear, world, { joint_a = j.pin, joint_b = j.motor, ratio = 0 })
  refused("the same body twice", "add_weld: b must be another body than a", world.add_weld, world, { a = b.bob, b = b.bob, anchor = {0, 0} })
  refused("a pin without anchor", "add_revolute: anchor is required", world.add_revolute, world, { a = b.bob })
  refused("a pulley without b", "add_pulley: b is required: a pulley joins two bodies",
          world.add_pulley, world, { a = b.bob, ground_a = {0, 0}, ground_b = {1, 0} })
  refused("a pulley without ground", "add_pulley: ground_a is required", world.add_pulley, world, { a = b.left, b = b.right })
  refused("a rope to the world without its end", "add_distance: anchor_b is required", world.add_distance, world, { a = b.bob })
  refused("a revolute option on a prismatic", "add_prismatic: unknown option 'lower_angle' (did you mean 'lower'?)",
          world.add_prismatic, world, { a = b.slider, anchor = {0, 0}, axis = {1, 0}, lower_angle = 1 })
  refused("a field of another kind", "revolute joint: has no field 'lower' (did you mean 'lower_angle'?)", function() return j.pin.lower end)
  refused("a read-only field", "joint.joint_a: is read-only", function() j.gear.joint_a = j.pin end)
  refused("a write past the bound", "joint.lower_angle: lower_angle (1) must not exceed upper_angle (0.5)",
          function() j.limit.lower_angle = 1 end)
  refused("break_force 0", "joint.break_force: must be > 0, got 0", function() j.pin.break_force = 0 end)
  refused("break_force nan", "add_weld: break_force must be finite or math.huge, got nan",
          world.add_weld, world, { a = b.bob, anchor = {0, 0}, break_force = 0 / 0 })
  refused("set_limits of a weld", "weld joint: has no field 'set_limits'", function() return j.weld.set_limits end)
end

local steps = 0
function OnStep(world, dt)
  steps = steps + 1
  local function gap(joint) return (joint.anchor_a - joint.anchor_b):length() end
  worst.pin = math.max(worst.pin, gap(j.pin), gap(j.motor))
  worst.gear = math.max(worst.gear, math.abs(j.axle_big.angle + 2 * j.axle_small.angle))
  local ga, gb = j.pulley.ground_a, j.pulley.ground_b
  worst.pulley = math.max(worst.pulley, math.abs((j.pulley.anchor_a - ga):length() + (j.pulley.anchor_b - gb):length() - pulley_length0))
  worst.rigid = math.max(worst.rigid, math.abs(j.rod.translation - 2))
  check.near("a pinned body's angle is the joint's", j.pin.angle, b.pendulum.angle, 1e-12)
  check.near("and its speed", j.pin.speed, b.pendulum.angular_velocity, 1e-12)
  if steps == 60 then
    -- The friction joint takes at most max_force: the sled slows by 4 N / 2 kg.
    check.near("friction joint brakes at max_force / m", b.sled.velocity.x, 3 - 2 * world.time, 1e-9)
  end
  if steps == 30 then
    check.that("the bracket holds the shelf", not j.bracket.removed)
    b.shelf:apply_impulse({0, -5})  -- 300 N over a step
  elseif steps == 31 then
    check.that("the bracket broke", j.bracket.broken and j.bracket.removed)
    check.that("find_joint no longer finds it", world:find_joint("bracket") == nil)
    refused("a broken joint's fields", "joint.reaction_force: the weld joint broke and was removed",
            function() return j.bracket.reaction_force end)
  end
end

function Check(world)
  check.less("pin gap", worst.pin, 1e-9)
  check.near("motor speed", j.motor.speed, 2, 1e-6)
  check.near("the wheel turns counter-clockwise", b.wheel.angular_velocity, 2, 1e-6)
  check.near("arm held at its lower limit", j.limit.angle, -0.5, 2e-3)
  check.near("the arm's own angle", b.arm.angle, -0.5, 2e-3)
  check.near("the limit holds the arm's weight: m g (L / 2) cos θ", j.limit.reaction_torque, 5 * 10 * 1 * math.cos(0.5), 0.05)
  check.near("slider at its upper limit", j.slide.translation, 1, 2e-3)
  check.near("slider on its axis", b.slider.position.x - 30 + b.slider.position.y - 20, 0, 1e-3)
  check.near("slider motor speed", j.drive.speed, 0.5, 1e-6)
  check.near("rope taut at its max_length", j.rope.translation, 2, 5e-3)
  check.less("rod length kept", worst.rigid, 1e-6)
  check.less("weld keeps the hammer's shape", math.abs(j.weld.angle), 1e-3)
  -- The tyre touches nothing: it is integrated with its joint (exact_joints), the spring a force
  -- m ω² x + 2 m ω x' (ζ = 1) at every stage, so it settles on g / ω² (the contact solvers' soft
  -- spring, after the step, rested 1.4 mm higher: g h² / 2); it falls asleep 3 µm short of it, when
  -- its speed stays under the sleep speed.
  check.near("wheel sags by g / ω²", j.wheel.translation, -10 / (2 * math.pi * 2) ^ 2, 1e-5)
  check.near("motor joint reached its target x", b.puck.position.x, 92, 1e-3)
  check.near("motor joint reached its target y", b.puck.position.y, 21, 1e-3)
  check.near("motor joint reached its target angle", b.puck.angle, 1, 1e-3)
  check.near("and stops", b.sled.velocity.x, 0, 1e-9)
  check.less("pulley rope length", worst.pulley, 1e-3)
  check.less("heavier side down", b.left.position.y, 19.5)
  check.less("gear ratio", worst.gear, 1e-9)
  check.near("gear speeds", b.small.angular_velocity, -0.5 * b.big.angular_velocity, 1e-9)
  check.greater("still turning", math.abs(b.big.angular_velocity), 1)
end
