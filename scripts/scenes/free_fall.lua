-- Free fall for 10 s from y = 0 (the thesis's Table 4.1, docs/design/thesis.md §5). Run it with any integrator
-- and step; the Check knows what each must give:
--   RK4                   exact for constant acceleration: y = −½ g T², round-off only
--   explicit Euler        y_N = −½ g T (T − h)   (the thesis's "Euler" column)
--   semi-implicit Euler   y_N = −½ g T (T + h)
--     rigidlab run scripts/scenes/free_fall.lua --integrator euler --dt 0.01
local check = require "check"

scene = { title = "Free fall (Table 4.1)", dt = 0.1, duration = 10, integrator = "rk4",
          camera = { center = {0, -245}, height = 520 } }

local g = 9.80665

-- The thesis's published values (Table 4.1), which the closed forms reproduce.
local table_4_1 = {
  rk4 = { [1] = -490.33249999999998, [0.1] = -490.33250000000027 },
  euler = { [0.1] = -485.42917500000027, [0.01] = -489.84216750000547, [0.001] = -490.28346675005253 },
}

function PopulateWorld(world)
  world:add_circle{ name = "ball", radius = 0.5 }
end

function Check(world)
  local T, h = world.time, world.dt
  check.near("simulated time", T, 10, 1e-9)
  local y = world:find("ball").position.y
  local expected, tolerance
  if world.integrator == "rk4" then
    -- Round-off grows with the number of steps: |err| ≤ 4 N ε |y| (docs/design/accuracy.md §3.1).
    expected, tolerance = -0.5 * g * T * T, math.max(1e-9, 4 * (T / h) * 2.2e-16 * 490.3325)
  elseif world.integrator == "euler" then
    expected, tolerance = -0.5 * g * T * (T - h), 1e-6
  else
    expected, tolerance = -0.5 * g * T * (T + h), 1e-6
  end
  check.near("y(10 s) against the closed form", y, expected, tolerance)
  local published = (table_4_1[world.integrator] or {})[h]
  if published then check.near("y(10 s) against Table 4.1", y, published, 1e-6) end
  print(string.format("%s, h = %g: y(10) = %.14f (closed form %.14f)", world.integrator, h, y, expected))
end
