-- Four ragdolls of revolute joints with limits (neck, shoulders, elbows, hips, knees) dropped onto
-- the ground on top of each other, turned this way and that (scripts/ragdoll.lua builds them: each
-- ragdoll's parts share a negative group, so its own limbs pass through each other and only the
-- joints hold them). Checks: the pins hold (anchor gaps), and no joint ends past its limits.
-- ragdoll_drop.lua drops them from 5 m.
local check = require "check"
local watch = require "watch"
local ragdoll = require "ragdoll"

scene = { title = "Ragdoll pile", dt = 1/60, duration = 2.5, camera = { center = {0, 2.5}, height = 7 } }

local joints = {}
local worst_gap, worst_past, worst_past_final = 0, 0, 0

function PopulateWorld(world)
  world:add_box{ width = 20, height = 1, position = {0, -0.5}, static = true }
  for i = 1, 4 do
    ragdoll.add(world, vec2(0.3 * (i % 2) - 0.15, 1.5 + 1.6 * i), 1.3 * i, -i, joints)
  end
end

function OnStep(world, dt)
  worst_gap = math.max(worst_gap, watch.gap(joints))
  worst_past = math.max(worst_past, watch.past_limits(joints))
  if world.time > scene.duration - 0.5 then worst_past_final = math.max(worst_past_final, watch.past_limits(joints)) end
end

function Check(world)
  print(string.format("%d joints: worst gap %.2g m, past a limit by %.4f rad (at most), %.4f rad in the last 0.5 s",
                      #joints, worst_gap, worst_past, worst_past_final))
  check.that("36 joints, none lost", #world:joints() == 36)
  -- Bounds from the measured values with margin: gap 1.2e-12 m; past a limit by 0.0403 rad while
  -- they land, 0.0047 rad in the pile (2026-12-07). The landing's overshoot is the contact solvers'
  -- soft limits (docs/physics.md): they take a ragdoll's joints the step it first touches. In the
  -- air its joints are exact and keep its limbs' swing undamped, so it lands with more of it than
  -- when the contact solvers held the joints all the way down (exact_joints = false: 0.0181 rad,
  -- at step 70 of the same run, against 0.0403 at step 71).
  check.less("the pins hold", worst_gap, 1e-6)
  check.less("limits respected while they land", worst_past, 0.06)
  check.less("limits respected in the pile", worst_past_final, 0.01)
end
