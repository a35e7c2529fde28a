-- Builds a world from the data table of a scene file saved by the sandbox (engine/lua/src/
-- scene_writer.cpp writes it). Uses only the public scene API, so a saved scene goes through the
-- same validation as a hand-written one.
--
--   function PopulateWorld(world)
--     require("saved_world").populate(world, data)
--   end
--
-- data = {
--   version = 2,
--   bodies = { {"circle", r, x, y, angle, vx, vy, w, mass, restitution, friction, static_friction,
--               static [, name]} or {"polygon", {{x, y}, ...}, x, y, ...} },  -- one row per body
--   springs = { {a = i, b = j or anchor = {x, y}, local_a, local_b, stiffness, rest_length, damping} },
--   dampers = { {body = i, coefficient = c, angular_coefficient = c_w} },
-- }
-- Springs and dampers name their bodies by index in data.bodies. Version 1 files (rigidlab before
-- the rows) name every body field: {shape = "circle", radius = r, position = {x, y}, angle = a, ...}.

local saved_world = {}

local SUPPORTED_VERSIONS = {[1] = true, [2] = true}

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
    error(string.format("saved_world: bodies[%d].shape must be \"circle\" or \"polygon\", got %s",
                        index, tostring(b.shape)), 3)
  end
  return args
end

function saved_world.populate(world, data)
  if type(data) ~= "table" then error("saved_world.populate: data must be a table", 2) end
  if not SUPPORTED_VERSIONS[data.version] then
    error(string.format("saved_world: data.version %s is not supported (this rigidlab reads 1 and 2)",
                        tostring(data.version)), 2)
  end

  local bodies = {}
  for i, b in ipairs(data.bodies or {}) do  -- ipairs: creation order is part of the state
    if data.version == 2 then b = row_fields(b) end
    local args = body_args(b, i)
    if b.shape == "circle" then
      bodies[i] = world:add_circle(args)
    else
      bodies[i] = world:add_polygon(args)
    end
  end

  local function body(index, where)
    local b = bodies[index]
    if b == nil then
      error(string.format("saved_world: %s names body %s, but data.bodies has %d", where,
                          tostring(index), #bodies), 3)
    end
    return b
  end

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

  return bodies
end

return saved_world
