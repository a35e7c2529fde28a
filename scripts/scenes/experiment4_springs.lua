-- Experiment 4 of the thesis (docs/design/thesis.md §12.4): springs. All weights are 3 kg and start displaced.
--   A      an undamped spring                         keeps oscillating with its initial amplitude
--   B      a damped spring                            comes to rest at its equilibrium
--   C, D   two undamped springs holding one weight    keeps oscillating with its initial amplitude
--   E,F,G  three damped springs whose weights carry   all come to rest
--          the rectangle O (hung from them on short
--          damped springs)
-- Hooke's law F = −k x (docs/design/thesis.md §1, §4); as in the thesis a damped spring's weight also carries a
-- damper F = −c v, which calms sideways swinging too (damping along the spring alone would not).
-- A hanging weight's equilibrium stretch is m g / k; released from rest, an undamped weight turns
-- around at its starting height every period.
local check = require "check"

scene = { title = "Experiment 4: springs", duration = 30, camera = { center = {-1, 7}, height = 8 } }

local g, m, k = 9.80665, 3.0, 100.0
local ceiling, rest = 10.0, 2.0
local equilibrium = ceiling - rest - m * g / k      -- 7.7058 m
local pull = 0.5                                    -- initial displacement below equilibrium
local lowest, highest = {}, {}

local function weight(world, name, x, y)
  return world:add_box{ name = name, width = 0.6, height = 0.6, position = {x, y}, mass = m }
end

function PopulateWorld(world)
  local a = weight(world, "A", -7, equilibrium - pull)
  world:add_spring{ a = a, anchor = {-7, ceiling}, stiffness = k, rest_length = rest }

  local b = weight(world, "B", -5, equilibrium - pull)
  world:add_spring{ a = b, anchor = {-5, ceiling}, stiffness = k, rest_length = rest }
  world:add_damper{ body = b, coefficient = 6 }

  -- C and D share the weight from anchors 0.5 m to either side; released 0.4 m low.
  local cd = weight(world, "CD", -2.5, 7.2)
  world:add_spring{ a = cd, anchor = {-3, ceiling}, stiffness = k, rest_length = rest }
  world:add_spring{ a = cd, anchor = {-2, ceiling}, stiffness = k, rest_length = rest }

  local o = world:add_box{ name = "O", width = 4, height = 0.3, position = {3.5, 6.3}, angle = 0.1, mass = m }
  for i, name in ipairs{ "E", "F", "G" } do
    local x = 0.5 + 1.5 * i
    local w = weight(world, name, x, equilibrium - pull * i / 3)
    world:add_spring{ a = w, anchor = {x, ceiling}, stiffness = 3 * k, rest_length = rest }
    world:add_damper{ body = w, coefficient = 6, angular_coefficient = 1 }
    world:add_spring{ a = w, b = o, local_a = {0, -0.3}, local_b = {x - 3.5, 0.15}, stiffness = 3 * k,
                      rest_length = 0.3, damping = 15 }
  end
end

function OnStep(world, dt)
  if world.time < world.dt or world.time > 27 then  -- the first step and the last three seconds
    for _, name in ipairs{ "A", "CD" } do
      local y = world:find(name).position.y
      lowest[name] = math.min(lowest[name] or y, y)
      highest[name] = math.max(highest[name] or y, y)
    end
  end
end

function Check(world)
  -- Undamped: still turning around at the starting height, with the full swing.
  check.near("A lowest point in the last 3 s", lowest.A, equilibrium - pull, 1e-3)
  check.near("A swing in the last 3 s", highest.A - lowest.A, 2 * pull, 2e-3)
  check.near("C+D lowest point in the last 3 s", lowest.CD, 7.2, 1e-3)
  check.greater("C+D swing in the last 3 s", highest.CD - lowest.CD, 0.5)
  -- Damped: at rest.
  for _, name in ipairs{ "B", "E", "F", "G", "O" } do
    check.less(name .. " speed", world:find(name).velocity:length(), 1e-3)
  end
  check.near("B at its equilibrium", world:find("B").position.y, equilibrium, 1e-3)
end
