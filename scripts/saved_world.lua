-- Builds a world from the data table of a scene file saved by the sandbox (engine/lua/src/
-- scene_writer.cpp writes it). The one place where the saved rows become scene API calls, and it
-- uses only the public scene API, so a saved scene goes through the same validation as a
-- hand-written one.
--
--   function PopulateWorld(world)
--     require("saved_world").populate(world, data)
--   end
--
-- data = {
--   version = 3,
--   bodies = { {kind, geometry, x, y, angle, vx, vy, w, density, restitution, friction,
--               static_friction, type [, name [, more]]} },                -- one row per body
--   joints = { {kind = "revolute", a = i, b = j, anchor = {x, y}, ..., made_at = {x, y, angle}} },
--   springs = { {a = i, b = j or anchor = {x, y}, local_a, local_b, stiffness, rest_length, damping} },
--   dampers = { {body = i, coefficient = c, angular_coefficient = c_w} },
-- }
-- A body row: its first shape (kind and geometry in body coordinates: "circle", radius |
-- "polygon", {{x, y}, ...} | "capsule", {a, b, radius} | "segment", {a, b} | "chain", {{x, y}, ...}),
-- the origin's position and angle, the centre of mass's velocity, the first shape's density and
-- material, the type ("static", "kinematic", "dynamic"), the name ("" for none), and `more`, the
-- options that are not at their defaults: body options (linear_damping, angular_damping,
-- gravity_scale, gravity, sleeping_allowed, fixed_rotation, bullet, enabled), the first shape's
-- filter, sensor flag and surface (category, mask, group, sensor, tangent_speed,
-- rolling_resistance), `loop` for a chain, and `shapes`: the body's other shapes as body:add_shape
-- options.
-- Joints name their bodies by index in data.bodies (b absent: the world) and a gear its joints by
-- index in data.joints (a gear of two bodies' angles its bodies, a and b); the other fields are
-- the options of world:add_<kind>. `made_at`: a joint
-- is made at the pose of its bodies, which sets its zero angle and anchors, so body b (a when b is
-- the world) is put at that pose while the joint is made, then back.
-- Springs and dampers name their bodies by index in data.bodies.
-- Version 2 rows (rigidlab before shapes and joints): {"circle", r | "polygon", {{x, y}, ...}, x, y,
-- angle, vx, vy, w, mass, restitution, friction, static_friction, static [, name]}. Version 1 files
-- name every body field: {shape = "circle", radius = r, position = {x, y}, angle = a, ...}.
--
-- Options are passed only when they differ from the API's defaults, so a saved world that uses
-- only what older scene APIs had (one-shape circles and polygons, static or dynamic) loads there.

local saved_world = {}

local SUPPORTED_VERSIONS = {[1] = true, [2] = true, [3] = true}

local JOINT_FUNCTIONS = {
  revolute = "add_revolute", prismatic = "add_prismatic", distance = "add_distance", weld = "add_weld",
  wheel = "add_wheel", motor = "add_motor_joint", friction = "add_friction_joint", pulley = "add_pulley",
  gear = "add_gear",
}

local function fail(message, ...)
  error("saved_world: " .. string.format(message, ...), 0)
end

-- A version 2 row as the named fields of version 1.
local function row_fields(row)
  local fields = {
    position = {row[3], row[4]}, angle = row[5], velocity = {row[6], row[7]}, angular_velocity = row[8],
    mass = row[9], restitution = row[10], friction = row[11], static_friction = row[12], static = row[13],
    name = row[14], shape = row[1],
  }
  if row[1] == "circle" then fields.radius = row[2] else fields.vertices = row[2] end
  return fields
end

local function body_args(b, index)
  local args = {
    position = b.position, angle = b.angle,
    velocity = b.velocity, angular_velocity = b.angular_velocity,
    mass = b.mass, restitution = b.restitution,
    friction = b.friction, static_friction = b.static_friction,
    static = b.static, name = b.name,
  }
  if b.shape == "circle" then
    args.radius = b.radius
  elseif b.shape == "polygon" then
    args.vertices = b.vertices
  else
    fail("bodies[%d].shape must be \"circle\" or \"polygon\", got %s", index, tostring(b.shape))
  end
  return args
end

-- Versions 1 and 2.
local function add_old_body(world, b, index)
  local args = body_args(b, index)
  if b.shape == "circle" then return world:add_circle(args) end
  return world:add_polygon(args)
end

local BODY_OPTIONS = {"linear_damping", "angular_damping", "gravity_scale", "fixed_rotation", "bullet", "enabled",
                      "category", "mask", "group", "sensor", "gravity", "sleeping_allowed", "tangent_speed",
                      "rolling_resistance"}

-- Version 3: the first shape by the world's shorthand for it, then the other shapes, then the
-- velocity (adding a shape moves the centre of mass, which would change the velocity of a body
-- that turns).
local function add_body(world, row, index)
  local kind, geometry, more = row[1], row[2], row[15] or {}
  local body_type, name = row[13], row[14]
  local shapes = more.shapes or {}
  local args = {position = {row[3], row[4]}, angle = row[5], restitution = row[10], friction = row[11],
                static_friction = row[12]}
  if name ~= nil and name ~= "" then args.name = name end
  for _, key in ipairs(BODY_OPTIONS) do args[key] = more[key] end
  -- A chain is made on a static body; another type is set once the chain is in place.
  local later_type = nil
  if body_type == "static" or kind == "chain" then
    args.static = true
    if kind == "chain" and body_type ~= "static" then later_type = body_type end
  elseif body_type == "kinematic" then
    args.type = "kinematic"
  elseif body_type ~= "dynamic" then
    fail("bodies[%d]: type must be \"static\", \"kinematic\" or \"dynamic\", got %s", index, tostring(body_type))
  end
  local moving = body_type ~= "static"
  if moving and #shapes == 0 and later_type == nil then
    args.velocity = {row[6], row[7]}
    args.angular_velocity = row[8]
  end
  local body
  if kind == "circle" then
    args.radius, args.density = geometry, row[9]
    body = world:add_circle(args)
  elseif kind == "polygon" then
    args.vertices, args.density = geometry, row[9]
    body = world:add_polygon(args)
  elseif kind == "capsule" then
    args.a, args.b, args.radius, args.density = geometry[1], geometry[2], geometry[3], row[9]
    body = world:add_capsule(args)
  elseif kind == "segment" then
    args.a, args.b = geometry[1], geometry[2]
    body = world:add_segment(args)
  elseif kind == "chain" then
    args.points, args.loop = geometry, more.loop
    body = world:add_chain(args)
  else
    fail("bodies[%d]: unknown shape kind %s", index, tostring(kind))
  end
  for _, shape in ipairs(shapes) do body:add_shape(shape) end
  if later_type ~= nil then body.type = later_type end
  if moving and args.velocity == nil then
    body.velocity = {row[6], row[7]}
    body.angular_velocity = row[8]
  end
  return body
end

-- Everything of a joint row but what names other rows, as the options of world:add_<kind>.
local function add_joint(world, row, index, body, joint)
  local where = string.format("joints[%d]", index)
  local fn = JOINT_FUNCTIONS[row.kind]
  if fn == nil then fail("%s: unknown joint kind %s", where, tostring(row.kind)) end
  local args = {}
  for key, value in pairs(row) do
    if key ~= "kind" and key ~= "made_at" then args[key] = value end
  end
  if row.kind == "gear" and row.joint_a == nil then  -- a gear of two bodies' angles
    args.a = body(row.a, where .. ".a")
    args.b = body(row.b, where .. ".b")
  elseif row.kind == "gear" then
    args.joint_a = joint(row.joint_a, where .. ".joint_a")
    args.joint_b = joint(row.joint_b, where .. ".joint_b")
  else
    args.a = body(row.a, where .. ".a")
    if row.b ~= nil then args.b = body(row.b, where .. ".b") end
  end
  local moved, position, angle = nil, nil, nil
  if row.made_at ~= nil then
    moved = args.b or args.a
    position, angle = moved.position, moved.angle
    moved.position = {row.made_at[1], row.made_at[2]}
    moved.angle = row.made_at[3]
  end
  local made = world[fn](world, args)
  if moved ~= nil then
    moved.angle = angle
    moved.position = position
  end
  return made
end

function saved_world.populate(world, data)
  if type(data) ~= "table" then error("saved_world.populate: data must be a table", 2) end
  if not SUPPORTED_VERSIONS[data.version] then
    error(string.format("saved_world: data.version %s is not supported (this rigidlab reads 1, 2 and 3)",
                        tostring(data.version)), 2)
  end

  local bodies = {}
  for i, b in ipairs(data.bodies or {}) do  -- ipairs: creation order is part of the state
    if data.version == 3 then
      bodies[i] = add_body(world, b, i)
    else
      bodies[i] = add_old_body(world, data.version == 2 and row_fields(b) or b, i)
    end
  end

  local function body(index, where)
    local b = bodies[index]
    if b == nil then
      fail("%s names body %s, but data.bodies has %d", where, tostring(index), #bodies)
    end
    return b
  end

  local joints = {}
  local function joint(index, where)
    local j = joints[index]
    if j == nil then fail("%s names joint %s, which is not made before it", where, tostring(index)) end
    return j
  end
  for i, j in ipairs(data.joints or {}) do joints[i] = add_joint(world, j, i, body, joint) end

  for i, s in ipairs(data.springs or {}) do
    local where = string.format("springs[%d]", i)
    local args = {
      a = body(s.a, where .. ".a"), local_a = s.local_a,
      stiffness = s.stiffness, rest_length = s.rest_length, damping = s.damping,
    }
    if s.b ~= nil then
      args.b = body(s.b, where .. ".b")
      args.local_b = s.local_b
    else
      args.anchor = s.anchor
    end
    world:add_spring(args)
  end

  for i, d in ipairs(data.dampers or {}) do
    local args = {body = body(d.body, string.format("dampers[%d].body", i)), coefficient = d.coefficient}
    -- Only passed when used, so a scene API without angular dampers still loads linear ones.
    if d.angular_coefficient ~= nil and d.angular_coefficient ~= 0 then
      args.angular_coefficient = d.angular_coefficient
    end
    world:add_damper(args)
  end

  return bodies, joints
end

return saved_world
