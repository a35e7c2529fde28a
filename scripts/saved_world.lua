-- Builds a world from the data table of a scene file saved by the sandbox (engine/lua/src/
-- scene_writer.cpp writes it). Uses only the public scene API, so a saved scene goes through the
-- same validation as a hand-written one.
--
--   function PopulateWorld(world)
--     require("saved_world").populate(world, data)
--   end
--
-- data = {
--   version = 1,
--   bodies = { {shape = "circle", radius = r, ...} or {shape = "polygon", vertices = {{x, y}, ...}, ...} },
--     -- common body fields: position, angle, velocity, angular_velocity, mass, restitution,
--     -- friction, static_friction, static, name (as world:add_circle / world:add_polygon take them)
--   springs = { {a = i, b = j or anchor = {x, y}, local_a, local_b, stiffness, rest_length, damping} },
--   dampers = { {body = i, coefficient = c, angular_coefficient = c_w} },
-- }
-- Springs and dampers name their bodies by index in data.bodies.

local saved_world = {}

local SUPPORTED_VERSION = 1

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
  if data.version ~= SUPPORTED_VERSION then
    error(string.format("saved_world: data.version %s is not supported (this rigidlab reads %d)",
                        tostring(data.version), SUPPORTED_VERSION), 2)
  end

  local bodies = {}
  for i, b in ipairs(data.bodies or {}) do  -- ipairs: creation order is part of the state
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
