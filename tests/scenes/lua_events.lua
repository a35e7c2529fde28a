-- Event hooks through the Lua API: the order they are called in within one step (contact events,
-- then sensor events, then joint breaks, then OnStep), the contact table's names and values,
-- world:contact_events() agreeing with the hooks, and end events.
--
-- Three things happen in step 31 by construction (as in scripts/scenes/vase.lua): released from
-- rest, each falling body has fallen ½ g t0² by t0 = 0.5 s with 4 cm to go, out of the contact
-- margin, and gets there within the next step: box A lands on the floor (begin, hit), ball B enters
-- a sensor, and ball E lands with a light box welded on top, whose weld (break_force 1 N, unloaded
-- in free fall) breaks on the impact.
local check = require "check"

scene = { title = "Lua API: events", dt = 1 / 60, duration = 1.2, integrator = "rk4" }

local g = 9.80665
local fall = 0.5 * g * 0.25 + 0.04
local A, B, E, zone, weld
local log = {}
local hook_contacts, events_seen = {}, nil

local function note(what, detail) log[#log + 1] = { step = 0, what = what, detail = detail } end

function PopulateWorld(world)
  world:add_box{ name = "floor", width = 40, height = 1, position = {0, -0.5}, static = true }
  A = world:add_box{ name = "A", width = 0.5, height = 0.5, position = {0, fall + 0.25}, contact_events = true,
                     hit_speed = 2 }
  -- The sensor's top at y = 1: B's bottom falls to it as A's falls to the floor.
  zone = world:add_box{ name = "zone", width = 2, height = 0.5, position = {5, 0.75}, static = true, sensor = true }
  B = world:add_circle{ name = "B", radius = 0.2, position = {5, 1 + fall + 0.2} }
  E = world:add_box{ name = "E", width = 0.5, height = 0.5, position = {-5, fall + 0.25} }
  local F = world:add_box{ name = "F", width = 0.3, height = 0.3, position = {-5, fall + 0.65}, density = 4 }
  weld = world:add_weld{ a = E, b = F, anchor = {-5, fall + 0.5}, break_force = 1, name = "weld" }
end

function OnContactBegin(world, c)
  note("begin", c.b.name)
  hook_contacts[#hook_contacts + 1] = c
end
function OnHit(world, c) note("hit", c.b.name) end
function OnContactEnd(world, c) note("end", c.b.name) end
function OnSensorBegin(world, sensor, visitor) note("sensor_begin", sensor.body.name .. "<" .. visitor.body.name) end
function OnSensorEnd(world, sensor, visitor) note("sensor_end", sensor.body.name .. "<" .. visitor.body.name) end
function OnJointBreak(world, joint) note("joint_break", joint.kind .. (joint.broken and " broken" or "")) end

function OnStep(world)
  for _, entry in ipairs(log) do
    if entry.step == 0 then entry.step = world.step_count end
  end
  if world.step_count == 31 then
    note("step")
    log[#log].step = 31
    events_seen = world:contact_events()
  end
  if world.step_count == 50 then A.position = {0, 3} end  -- lifted: its contact ends next step
end

local function entries(step)
  local out = {}
  for _, entry in ipairs(log) do
    if entry.step == step then out[#out + 1] = entry.what .. (entry.detail and ":" .. entry.detail or "") end
  end
  return table.concat(out, " ")
end

function Check(world)
  check.that("step 31, in order", entries(31) == "begin:A hit:A sensor_begin:zone<B joint_break:weld broken step",
             entries(31))
  check.that("nothing before", entries(30) == "", entries(30))
  check.that("A's contact ends the step after it was lifted", entries(51) == "end:A", entries(51))
  check.that("the weld is gone", weld.broken and weld.removed)
  -- B falls through the sensor (which collides with nothing) and leaves it.
  local ended = false
  for _, entry in ipairs(log) do ended = ended or entry.what == "sensor_end" end
  check.that("B left the sensor", ended)

  -- The contact table: exactly these names.
  local c = hook_contacts[1]
  local names = {}
  for k in pairs(c) do names[#names + 1] = k end
  table.sort(names)
  check.that("contact fields", table.concat(names, ",") ==
             "a,approach_speed,b,normal,normal_impulse,point,points,shape_a,shape_b,tangent_impulse", table.concat(names, ","))
  check.that("bodies and shapes", c.a.name == "floor" and c.b == A and c.shape_b == A.shapes[1] and c.shape_a.body == c.a)
  check.near("normal from a to b", c.normal.y, 1, 1e-12)
  check.near("approach speed g t0", c.approach_speed, g * 0.5, 1e-9)
  check.greater("normal impulse", c.normal_impulse, 0)
  check.near("point on the floor", c.point.y, 0, 0.1)
  -- world:contact_events() in OnStep: the same events, with their kind.
  check.that("contact_events", #events_seen == 2 and events_seen[1].kind == "begin" and events_seen[2].kind == "hit")
  check.near("the same approach speed", events_seen[1].approach_speed, c.approach_speed, 0)
  check.near("the same impulse", events_seen[2].normal_impulse, c.normal_impulse, 0)
  check.that("no events now", #world:contact_events() == 0)
end
