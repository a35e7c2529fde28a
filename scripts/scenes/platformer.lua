-- A platformer character: a capsule with fixed_rotation that walks right, knows it stands on
-- something from its contacts (body:contacts(): a contact whose normal points up into it), jumps
-- through a one-way platform from below and lands on it, and collects three coins (sensors) in the
-- order it reaches them (OnSensorBegin, which removes each coin's body).
local check = require "check"

scene = { title = "Platformer (one-way platform, sensors, contacts)", dt = 1 / 60, duration = 2.5,
          camera = { center = {3, 2}, height = 7 } }

local player, platform
local walk_speed, jump_speed = 3, 8
local platform_top = 2.6
local coins, collected = {}, {}
local jumped, was_under, went_through, landed = false, false, false, false
local grounded_steps, airborne_steps = 0, 0

-- Standing: a touching contact that pushes the player up (the normal from a to b points down
-- into the ground when the player is a, up into the player when it is b).
local function grounded(body)
  for _, c in ipairs(body:contacts()) do
    local up = c.b == body and c.normal.y or -c.normal.y
    if up > 0.7 then return true end
  end
  return false
end

function PopulateWorld(world)
  world:add_box{ name = "ground", width = 30, height = 1, position = {5, -0.5}, static = true, friction = 0.8 }
  platform = world:add_box{ name = "platform", width = 4, height = 0.2, position = {4.5, platform_top - 0.1},
                            static = true, one_way = {0, 1}, friction = 0.8 }
  -- 1 m tall: the segment's ends 0.25 m from its centre, radius 0.25.
  player = world:add_capsule{ name = "player", a = {0, -0.25}, b = {0, 0.25}, radius = 0.25, position = {0, 0.5},
                              fixed_rotation = true, friction = 0.8 }
  for i, p in ipairs{ {1, 0.5}, {3.2, 3.0}, {5.5, 3.1} } do
    coins[i] = world:add_circle{ name = "coin " .. i, radius = 0.2, position = p, static = true, sensor = true,
                                 user_data = i }
  end
end

function OnSensorBegin(world, sensor, visitor)
  if visitor.body ~= player then return end
  collected[#collected + 1] = sensor.body.user_data
  world:remove(sensor.body)
end

-- The variables the hooks change, in snapshots (docs/lua-api.md "Snapshots"): a run resumed from
-- a file, or rewound in the sandbox, carries on from the same decisions. `player`, `platform` and
-- `coins` are made by PopulateWorld and never change, so they need not be saved.
function SaveState(world)
  return { collected = collected, jumped = jumped, was_under = was_under, went_through = went_through,
           landed = landed, grounded_steps = grounded_steps, airborne_steps = airborne_steps }
end

function LoadState(world, s)
  collected, jumped, was_under, went_through = s.collected, s.jumped, s.was_under, s.went_through
  landed, grounded_steps, airborne_steps = s.landed, s.grounded_steps, s.airborne_steps
  -- A coin removed after the snapshot comes back without its user_data (the Lua side forgot it
  -- with the body): its number again.
  for i, coin in ipairs(coins) do
    if not coin.removed then coin.user_data = i end
  end
end

function OnStep(world)
  local p, on_ground = player.position, grounded(player)
  if on_ground then grounded_steps = grounded_steps + 1 else airborne_steps = airborne_steps + 1 end
  local v = player.velocity
  if on_ground and not jumped and p.x >= 2 then
    jumped = true
    player.velocity = {walk_speed, jump_speed}
  elseif on_ground then
    -- Walk until well onto the platform, then stand.
    player.velocity = {(landed and p.x > 5.8) and 0 or walk_speed, v.y}
  end
  -- Under the platform's span with the head below it, then above it with the feet over its top.
  local over_span = p.x > 2.5 and p.x < 6.5
  if over_span and p.y + 0.5 < platform_top - 0.2 then was_under = true end
  if was_under and over_span and p.y - 0.5 > platform_top then went_through = true end
  if jumped and on_ground and p.y > platform_top then landed = true end
end

function Check(world)
  check.that("jumped", jumped)
  check.that("jumped through the platform from below", went_through)
  check.that("landed on it", landed)
  check.near("stands on the platform's top", player.position.y - 0.5, platform_top, 0.01)
  check.that("grounded by its contacts", grounded(player))
  check.greater("steps on the ground", grounded_steps, 30)
  check.greater("steps in the air", airborne_steps, 30)
  check.near("upright (fixed rotation)", player.angle, 0, 0)
  check.that("three coins", #collected == 3, #collected .. " collected")
  for i = 1, 3 do
    check.that("coin " .. i .. " collected in order", collected[i] == i, tostring(collected[i]))
    check.that("coin " .. i .. " removed", coins[i].removed)
  end
end
