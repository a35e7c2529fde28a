-- Box2D v3's "washer" benchmark, built as rigidlab's C++ suite builds it (`rigidlab bench washer`,
-- engine/app/bench_suite.cpp): a kinematic drum turning at 25°/s about (0, 10) (and drifting at
-- (0.001, −0.002) m/s, as v3 sets it) holds 90 × 90 boxes of 0.2 m (8100, density 1, friction 0.6,
-- hit events on). The drum is a ring from 16 to 18 m of 36 quadrilaterals, each 10° wide plus 1°
-- over each neighbour, and 4 fins from 14 to 16 m, 10° wide, every 90°. v3 also makes a ground
-- body without shapes; so does this. Gravity (0, −10), sleeping on, 500 steps of 1/60 s. It
-- measures a dense pile kept tumbling by a kinematic body: nothing ever sleeps.
--
-- Check: the drum turns and drifts at its velocities exactly, and every box stays inside the ring.
local check = require "check"

local grid, a = 90, 0.1
local spin = math.pi / 180.0 * 25.0
scene = { title = "Benchmark: washer", gravity = {0, -10}, duration = 500 / 60, camera = { center = {0, 10}, height = 40 } }

local drum
local boxes = {}

function PopulateWorld(world)
  world:add_body{ type = "static" }
  drum = world:add_body{ type = "kinematic", position = {0.0, 10.0}, angular_velocity = spin, velocity = {0.001, -0.002} }
  local r0, r1, r2, step = 14.0, 16.0, 18.0, math.pi / 18.0
  local function at(r, angle) return { r * math.cos(angle), r * math.sin(angle) } end
  for i = 0, 35 do
    local t1, t2 = i * step, (i + 1) * step
    drum:add_shape{ shape = "polygon", vertices = { at(r1, t1 - 0.1 * step), at(r2, t1 - 0.1 * step), at(r2, t2 + 0.1 * step), at(r1, t2 + 0.1 * step) } }
    if i % 9 == 0 then
      drum:add_shape{ shape = "polygon", vertices = { at(r0, t1), at(r1, t1), at(r1, t2), at(r0, t2) } }
    end
  end
  local y = -1.1 * a * grid + 10.0
  for _ = 1, grid do
    local x = -1.1 * a * grid
    for _ = 1, grid do
      boxes[#boxes + 1] = world:add_box{ width = 2.0 * a, height = 2.0 * a, position = {x, y}, hit_events = true }
      x = x + 2.1 * a
    end
    y = y + 2.1 * a
  end
end

function Check(world)
  local t, farthest = world.time, 0
  local center = vec2(0.001 * t, 10.0 - 0.002 * t)
  for _, b in ipairs(boxes) do farthest = math.max(farthest, (b.position - drum.position):length()) end
  print(string.format("after %g s: drum angle %.6f rad (%.6f at its speed), %.3g m from its drifting centre; the farthest box %.4f m from the axis",
                      t, drum.angle, spin * t, (drum.position - center):length(), farthest))
  check.that("the ground, the drum (40 shapes) and 8100 boxes",
             #world:bodies() == 8102 and #boxes == 8100 and #drum.shapes == 40)
  check.near("the drum turns at 25°/s", drum.angle, spin * t, 1e-9)
  check.less("and drifts as it was told", (drum.position - center):length(), 1e-9)
  -- A box lying on the ring's inner face (16 m) has its centre 15.9 m from the axis; one outside
  -- the ring would read above 16.
  check.less("every box inside the ring", farthest, 15.95)
end
