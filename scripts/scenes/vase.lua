-- A vase that breaks when it lands hard: OnHit reads the impact's normal impulse and replaces the
-- vase by four shards above a threshold; a second vase, dropped from lower, survives its hit.
--
-- The hit's approach_speed is the closing speed at the start of the step in which the contact
-- began (contact_events.cpp), so the scene is laid out to make that step known: released from
-- rest, the tall vase has fallen h = ½ g t0² by t0 = 0.5 s (step 30 of 1/60 s; RK4 is exact for
-- constant gravity), when its bottom is still 4 cm above the floor: out of the 2 cm contact margin
-- (so no speculative contact slows it before) and less than the next step's 8 cm of travel. It
-- touches in step 31, and approach_speed = g t0 = sqrt(2 g h).
local check = require "check"

scene = { title = "Vase (hit events)", dt = 1 / 60, duration = 1.5, integrator = "rk4",
          camera = { center = {0, 1}, height = 4 } }

local g = 9.80665
local t0 = 0.5
local h = 0.5 * g * t0 * t0  -- 1.22583125 m
local gap = 0.04             -- the vase's bottom above the floor at t0
local break_impulse = 1.0    -- N·s: the vase (0.25 kg) hits with about m v = 1.23 N·s
local tall, low
local hits, shards = {}, {}

local function vase(world, name, x, drop)
  return world:add_box{ name = name, width = 0.5, height = 0.5, position = {x, drop + 0.25},
                        hit_speed = 0.5, user_data = { drop = drop } }
end

function PopulateWorld(world)
  world:add_box{ name = "floor", width = 20, height = 1, position = {0, -0.5}, static = true }
  tall = vase(world, "tall vase", 0, h + gap)
  low = vase(world, "low vase", 2, 0.1)
end

function OnHit(world, contact)
  local v = contact.b.user_data and contact.b or contact.a
  hits[#hits + 1] = { name = v.name, step = world.step_count, approach_speed = contact.approach_speed,
                      normal_impulse = contact.normal_impulse }
  if contact.normal_impulse > break_impulse then
    -- Removed inside the hook; the shards fly off from where it broke.
    local p = v.position
    world:remove(v)
    for i, offset in ipairs{ {-0.13, -0.13}, {0.13, -0.13}, {-0.13, 0.13}, {0.13, 0.13} } do
      shards[i] = world:add_box{ name = "shard", width = 0.2, height = 0.2,
                                 position = {p.x + offset[1], p.y + offset[2]},
                                 velocity = {offset[1] * 10, 1 + offset[2] * 5} }
    end
  end
end

function Check(world)
  check.that("two hits", #hits == 2, #hits .. " hits")
  local first = hits[1].name == "tall vase" and hits[1] or hits[2]
  local second = hits[1].name == "tall vase" and hits[2] or hits[1]
  check.near("the tall vase touches in step 31", first.step, 31, 0)
  check.near("approach speed = sqrt(2 g h)", first.approach_speed, math.sqrt(2 * g * h), 1e-6)
  check.greater("the tall vase's impulse", first.normal_impulse, break_impulse)
  check.that("the tall vase broke", tall.removed)
  check.that("into four shards", #shards == 4)
  for i, s in ipairs(shards) do check.less("shard " .. i .. " on the floor", s.position.y, 0.2) end
  -- The low one fell 0.1 m, touching in some step with the speed it had then (< sqrt(2 g 0.1)).
  check.less("the low vase's approach speed", second.approach_speed, math.sqrt(2 * g * 0.1) + 1e-9)
  check.less("the low vase's impulse", second.normal_impulse, break_impulse)
  check.that("the low vase survived", not low.removed)
  check.near("and stands on the floor", low.position.y, 0.25, 0.01)
end
