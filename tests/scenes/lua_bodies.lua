-- Body types and properties through the Lua API: type (kinematic bodies, set_target), static
-- velocities refused, damping, gravity scale, fixed rotation, bullet, enabled, user_data (any
-- value, kept as it is), add_body, and every field read back after it is set.
local check = require "check"

scene = { title = "Lua API: bodies", duration = 1, integrator = "rk4", gravity = {0, -10} }

local function refused(name, text, f, ...)
  local ok, message = pcall(f, ...)
  check.that(name .. " is refused", not ok, "no error")
  check.that(name .. ": message", message:find(text, 1, true) ~= nil, message)
end

local kin, target, half, none, fixed, off, damped, data, tagged

function PopulateWorld(world)
  -- Every body option read back.
  data = { answer = 42 }
  local b = world:add_box{ width = 1, height = 1, position = {100, 0}, type = "dynamic", linear_damping = 0.5,
                           angular_damping = 0.25, gravity_scale = 2, fixed_rotation = true, bullet = true,
                           enabled = true, user_data = data, name = "all", sensor = true, category = 8, mask = 12,
                           group = 3, restitution = 0.5, friction = 0.25, static_friction = 0.75 }
  check.that("type", b.type == "dynamic" and b.static == false)
  check.near("linear_damping", b.linear_damping, 0.5, 0)
  check.near("angular_damping", b.angular_damping, 0.25, 0)
  check.near("gravity_scale", b.gravity_scale, 2, 0)
  check.that("flags", b.fixed_rotation and b.bullet and b.enabled and b.sensor)
  check.that("filter", b.category == 8 and b.mask == 12 and b.group == 3)
  check.that("material", b.restitution == 0.5 and b.friction == 0.25 and b.static_friction == 0.75)
  check.that("user_data is the same table, not a copy", rawequal(b.user_data, data))
  data.answer = 43
  check.near("changes to it show", b.user_data.answer, 43, 0)
  check.that("shapes of a one-shape body", #b.shapes == 1 and b.shapes[1].kind == "polygon" and b.shape == "polygon")

  -- Writes, read back.
  b.linear_damping, b.angular_damping, b.gravity_scale = 1, 2, -1
  b.fixed_rotation, b.bullet, b.sensor = false, false, false
  b.category, b.mask, b.group = 1, -1, 0
  check.that("written", b.linear_damping == 1 and b.angular_damping == 2 and b.gravity_scale == -1 and
                        not b.fixed_rotation and not b.bullet and not b.sensor and b.mask == -1)
  for _, value in ipairs{ "text", 3.5, true, false, print, b, vec2(1, 2) } do
    b.user_data = value
    check.that("user_data round trip of " .. tostring(value), rawequal(b.user_data, value))
  end
  b.user_data = nil
  check.that("user_data cleared", b.user_data == nil)
  b.type = "kinematic"
  check.that("type written", b.type == "kinematic" and not b.static and b.mass == 1)
  b.static = true
  check.that("static = true is type static", b.type == "static" and b.static)
  b.type = "dynamic"

  -- A static body cannot move: an option or a write that would move it says why.
  local wall = world:add_box{ width = 1, height = 1, position = {110, 0}, static = true }
  refused("a static body's velocity", 'body.velocity: a static body cannot move, got (1, 0): make it kinematic (body.type = "kinematic") to give it a velocity',
          function() wall.velocity = {1, 0} end)
  refused("a static body's angular velocity", "body.angular_velocity: a static body cannot turn, got 2",
          function() wall.angular_velocity = 2 end)
  wall.velocity = {0, 0}  -- zero is fine
  refused("a static body made with a velocity",
          'add_box: velocity must be zero for a static body, got (0, 1) (a static body cannot move: make it type = "kinematic" to move it by its velocity)',
          world.add_box, world, { width = 1, height = 1, type = "static", velocity = {0, 1} })
  refused("type and static", 'add_box: static and type cannot both be given (static = true is type = "static")',
          world.add_box, world, { width = 1, height = 1, type = "static", static = true })
  refused("an unknown type", 'add_circle: type must be "static", "kinematic" or "dynamic", got "kinetic"',
          world.add_circle, world, { radius = 1, type = "kinetic" })
  refused("body.type", 'body.type: must be "static", "kinematic" or "dynamic", got 3', function() wall.type = 3 end)
  refused("set_target on a static body", 'set_target: moves kinematic bodies, and this one is static (make it type = "kinematic")',
          wall.set_target, wall, { position = {0, 0}, time = 1 })
  refused("set_target without time", "set_target: time is required", wall.set_target, wall, { position = {0, 0} })
  refused("body.linear_damping -1", "body.linear_damping: must be >= 0, got -1", function() wall.linear_damping = -1 end)
  refused("body.bullet 1", "body.bullet: must be true or false, got 1", function() wall.bullet = 1 end)
  refused("body.shapes", "body.shapes: is read-only", function() wall.shapes = {} end)
  refused("a misspelt field", "body: has no field 'gravity_scal' (did you mean 'gravity_scale'?)", function() return wall.gravity_scal end)

  -- A body without shapes.
  local empty = world:add_body{ position = {120, 0}, gravity_scale = 0, user_data = "empty" }
  check.that("add_body", #empty.shapes == 0 and empty.shape == nil and empty.user_data == "empty")
  refused("a shape option for add_body", "add_body: friction is an option of a shape, and add_body makes a body without shapes: give it to body:add_shape{...}",
          world.add_body, world, { friction = 1 })
  refused("a material write without shapes", "body.friction: the body has no shapes (add one with body:add_shape{...})",
          function() empty.friction = 1 end)

  -- Motion: a kinematic platform moves by its velocity only; set_target reaches the pose.
  kin = world:add_box{ width = 2, height = 0.2, type = "kinematic", velocity = {1, 0}, position = {0, 10} }
  target = world:add_box{ width = 1, height = 1, type = "kinematic", position = {20, 10} }
  target:set_target{ position = {23, 11}, angle = 0.5, time = 1 }
  check.near("set_target's velocity", target.velocity.x, 3, 1e-12)
  -- Gravity scales: half falls half as far, none not at all (RK4 is exact for constant gravity).
  half = world:add_circle{ radius = 0.5, position = {30, 10}, gravity_scale = 0.5 }
  none = world:add_circle{ radius = 0.5, position = {32, 10}, gravity_scale = 0 }
  -- Fixed rotation: an off-centre impulse moves it without turning it.
  fixed = world:add_box{ width = 1, height = 1, position = {40, 10}, fixed_rotation = true, gravity_scale = 0 }
  fixed:apply_impulse({0, 1}, fixed.position + vec2(0.5, 0))
  check.near("fixed rotation: no spin", fixed.angular_velocity, 0, 0)
  -- A disabled body stays where it is until enabled.
  off = world:add_circle{ radius = 0.5, position = {50, 10}, enabled = false }
  -- Damping: v = v0 / (1 + h c)^n, never flipped.
  damped = world:add_circle{ radius = 0.5, position = {60, 10}, gravity_scale = 0, velocity = {1, 0}, linear_damping = 6 }
  tagged = world:add_circle{ radius = 0.5, position = {70, 10}, user_data = data }
end

local steps = 0
function OnStep(world, dt)
  steps = steps + 1
  if steps == 30 then off.enabled = true end
end

function Check(world)
  local t = world.time
  check.near("kinematic platform x = v t", kin.position.x, t, 1e-12)
  check.near("kinematic platform: no gravity", kin.position.y, 10, 0)
  check.near("set_target x after 1 s", target.position.x, 23, 1e-9)
  check.near("set_target y", target.position.y, 11, 1e-9)
  check.near("set_target angle", target.angle, 0.5, 1e-9)
  check.near("gravity_scale 0.5", half.position.y, 10 - 0.25 * 10 * t * t, 1e-9)
  check.near("gravity_scale 0", none.position.y, 10, 0)
  check.near("fixed rotation: no angle", fixed.angle, 0, 0)
  check.near("fixed rotation: moved", fixed.position.y, 10 + t, 1e-9)
  local falling = t - 30 * world.dt
  check.near("disabled for 30 steps, then falling", off.position.y, 10 - 5 * falling * falling, 1e-9)
  -- RK4 (the default) evaluates linear_damping at its stages: v' = −c v gains its degree-4 Taylor
  -- factor per step, 1 − x + x²/2 − x³/6 + x⁴/24 with x = c h, close to e^(−c t).
  local x = 6 * world.dt
  check.near("damped", damped.velocity.x, (1 - x + x ^ 2 / 2 - x ^ 3 / 6 + x ^ 4 / 24) ^ steps, 1e-12)
  check.near("damped: as e^(-c t)", damped.velocity.x, math.exp(-6 * t), 1e-4)
  check.that("user_data kept through the steps", rawequal(tagged.user_data, data) and tagged.user_data.answer == 43)
  world:remove(tagged)
  check.that("a removed body is removed", tagged.removed)
end
