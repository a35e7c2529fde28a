-- Box2D v3's "rain" benchmark (rigidlab calls it ragdolls), built as rigidlab's C++ suite builds
-- it (`rigidlab bench ragdolls`, engine/app/bench_suite.cpp): ragdolls rain onto 5 floors, each
-- floor a row of 501 static 0.5 m boxes (one static body holds all 2505), gravity (0, −10),
-- sleeping on, 1000 steps of 1/60 s. Every 8 steps a column of 5 groups of 5 ragdolls appears, one
-- group 40 m above each floor; after 40 columns the oldest column is removed as each new one falls,
-- so the world holds at most 1000 ragdolls (11 000 bodies, 10 000 joints) and keeps changing. It
-- measures many small jointed islands falling, landing, piling up and going to sleep, with bodies
-- added and removed between steps (the OnStep hook does it after every 8th step, where the C++
-- scene does it before the next step: the same edits between the same steps).
--
-- A ragdoll is 11 capsules (hips, torso, head, upper and lower legs and arms) on 10 revolute joints
-- with limits, a weak motor at speed 0 as joint friction and a 5 Hz spring towards the rest pose;
-- the elbows rest bent by π/4 (reference_angle). Each lower leg carries a foot polygon that touches
-- only the floors. The i-th ragdoll of every group is in collision group −i: ragdolls at the same
-- place in their groups pass through each other, the others collide.
--
-- The slider `columns` (the sandbox's Controls panel, 1 to 40, read when the scene is built) keeps
-- fewer columns before the oldest is removed, for a lighter run; the benchmark is 40.
--
-- Check: the counts are what the schedule says, the pins hold (to 2 cm), no joint is further past
-- its limits than the elbows are built, and no ragdoll sinks into or falls through its floor.
local check = require "check"
local watch = require "watch"

local rows, group_size, grid_count, grid = 5, 5, 500, 0.5
local steps = 1000
scene = { title = "Benchmark: ragdolls (rain)", gravity = {0, -10}, duration = steps / 60,
          camera = { center = {0, 112}, height = 250 },
          controls = { { name = "columns", min = 1, max = 40, value = 40 } } }

-- bench_suite.cpp's bones: centre height, capsule ends and radius, parent, pivot height, limits
-- (× π), motor torque (× friction_torque), linear damping, reference angle (× π), has a foot
local bones = {
  { y = 0.95, y0 = -0.02, y1 = 0.02, r = 0.095 },                                                             -- hips
  { y = 1.2, y0 = -0.135, y1 = 0.135, r = 0.09, parent = 1, pivot = 1.0, lower = -0.25, upper = 0.0, friction = 0.5 },     -- torso
  { y = 1.475, y0 = -0.038, y1 = 0.039, r = 0.075, parent = 2, pivot = 1.4, lower = -0.3, upper = 0.1, friction = 0.25,
    damping = 0.1 },                                                                                          -- head
  { y = 0.775, y0 = -0.125, y1 = 0.125, r = 0.06, parent = 1, pivot = 0.9, lower = -0.05, upper = 0.4, friction = 1.0 },   -- upper left leg
  { y = 0.475, y0 = -0.155, y1 = 0.125, r = 0.045, parent = 4, pivot = 0.625, lower = -0.5, upper = -0.02, friction = 0.5,
    foot = true },                                                                                            -- lower left leg
  { y = 0.775, y0 = -0.125, y1 = 0.125, r = 0.06, parent = 1, pivot = 0.9, lower = -0.05, upper = 0.4, friction = 1.0 },   -- upper right leg
  { y = 0.475, y0 = -0.155, y1 = 0.125, r = 0.045, parent = 6, pivot = 0.625, lower = -0.5, upper = -0.02, friction = 0.5,
    foot = true },                                                                                            -- lower right leg
  { y = 1.225, y0 = -0.125, y1 = 0.125, r = 0.035, parent = 2, pivot = 1.35, lower = -0.1, upper = 0.8, friction = 0.5 },  -- upper left arm
  { y = 0.975, y0 = -0.125, y1 = 0.125, r = 0.03, parent = 8, pivot = 1.1, lower = -0.2, upper = 0.3, friction = 0.1,
    damping = 0.1, reference = 0.25 },                                                                        -- lower left arm
  { y = 1.225, y0 = -0.125, y1 = 0.125, r = 0.035, parent = 2, pivot = 1.35, lower = -0.1, upper = 0.8, friction = 0.5 },  -- upper right arm
  { y = 0.975, y0 = -0.125, y1 = 0.125, r = 0.03, parent = 10, pivot = 1.1, lower = -0.2, upper = 0.3, friction = 0.1,
    damping = 0.1, reference = 0.25 },                                                                        -- lower right arm
}
local foot = { {-0.03, -0.185}, {0.11, -0.185}, {0.11, -0.16}, {-0.03, -0.14} }
local friction_torque, hertz, damping = 0.05, 5.0, 0.5

-- One ragdoll standing with its feet at `x, y`, in collision group −group; returns its bodies.
local function add_human(world, x, y, group)
  local parts = {}
  for _, bone in ipairs(bones) do
    local body = world:add_capsule{ a = {0, bone.y0}, b = {0, bone.y1}, radius = bone.r, position = {x, y + bone.y},
                                    linear_damping = bone.damping or 0, friction = 0.2,
                                    category = 2, mask = 1 | 2, group = -group }
    if bone.foot then
      body:add_shape{ shape = "polygon", vertices = foot, friction = 0.05, category = 2, mask = 1, group = -group }
    end
    if bone.parent then
      world:add_revolute{ a = parts[bone.parent], b = body, anchor = {x, y + bone.pivot},
                          reference_angle = (bone.reference or 0) * math.pi,
                          lower_angle = bone.lower * math.pi, upper_angle = bone.upper * math.pi,
                          max_motor_torque = bone.friction * friction_torque, spring_hertz = hertz,
                          spring_damping = damping }
    end
    parts[#parts + 1] = body
  end
  return parts
end

-- What the rain has made: the bodies of each (row, column) place, and where the schedule is.
-- Saved with snapshots (SaveState), so a resumed or rewound run removes the right ragdolls.
local rain

-- A group of 5 ragdolls, 0.5 m apart, 40 m above floor `row`, at place `column`.
local function create(world, row, column)
  local span = grid_count * grid
  local distance = span / rain.columns
  local x, y = -0.5 * span + distance * (column + 0.5), 40.0 + 45.0 * row
  local group = {}
  for i = 1, group_size do
    for _, body in ipairs(add_human(world, x, y, i)) do group[#group + 1] = body end
    x = x + 0.5
  end
  rain.groups[row * rain.columns + column + 1] = group
end

-- Every 8th step: a new column, or once there are enough, the oldest replaced.
local function rain_step(world)
  if rain.column_count < rain.columns then
    for row = 0, rows - 1 do create(world, row, rain.column_count) end
    rain.column_count = rain.column_count + 1
    return
  end
  for row = 0, rows - 1 do
    for _, body in ipairs(rain.groups[row * rain.columns + rain.column_index + 1]) do world:remove(body) end
    create(world, row, rain.column_index)
  end
  rain.column_index = (rain.column_index + 1) % rain.columns
end

function PopulateWorld(world)
  rain = { columns = math.floor(world.controls.columns), groups = {}, column_count = 0, column_index = 0 }
  local ground = world:add_body{ type = "static" }
  for i = 0, rows - 1 do
    local x = -0.5 * grid_count * grid
    for _ = 0, grid_count do
      ground:add_shape{ shape = "box", width = grid, height = grid, offset = {x, 45.0 * i} }
      x = x + grid
    end
  end
  rain_step(world)  -- the first column falls from the first step
end

function OnStep(world)
  if world.step_count % 8 == 0 then rain_step(world) end
end

function SaveState(world) return rain end
function LoadState(world, saved) rain = saved end

function Check(world)
  local columns = math.min(rain.columns, world.step_count // 8 + 1)
  local joints = world:joints()
  local gap, past = watch.gap(joints), watch.past_limits(joints)
  local sunk = -math.huge  -- how far a bone's origin (on its capsule's axis) is below its floor's top
  for place, group in pairs(rain.groups) do
    local floor_top = 45.0 * ((place - 1) // rain.columns) + 0.5 * grid
    for _, body in ipairs(group) do sunk = math.max(sunk, floor_top - body.position.y) end
  end
  print(string.format("after %d steps: %d columns, %d bodies, %d joints; largest gap in a pin %.3g m, past a limit by %.3g rad, a bone %.3g m below its floor's top",
                      world.step_count, columns, #world:bodies(), #joints, gap, past, sunk))
  local ragdolls = columns * rows * group_size
  check.that("bodies: the floors and 11 per ragdoll", #world:bodies() == 1 + 11 * ragdolls)
  check.that("joints: 10 per ragdoll", #joints == 10 * ragdolls)
  -- Measured after the 1000 steps: 9.5 mm (0.7 mm after 330 steps, before the piles grow).
  check.less("largest gap in a pin", gap, 0.02)
  -- The elbows are built straight, π/20 below their lower limit (it counts from the π/4 they rest
  -- at), so the newest ragdolls are π/20 past it until their joints bring them in; none further.
  check.less("past a joint limit", past, math.pi / 20 + 0.01)
  check.less("a bone's axis below its floor's top", sunk, 0.05)
end
