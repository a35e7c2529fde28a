-- A pyramid of 1 m boxes, base 10 (55 boxes), standing on static ground for 10 s. The thesis names
-- stacks as the weak spot of linear projection (docs/design/thesis.md §9, §13); the Check holds the pyramid to
-- millimetres: every box stays where it was built and the top box stays on top.
local check = require "check"

local base = 10
scene = { title = "Pyramid (base 10)", duration = 10, camera = { center = {0, 5}, height = 14 } }

local built = {}

function PopulateWorld(world)
  world:add_box{ name = "ground", width = 40, height = 1, position = {0, -0.5}, static = true }
  for row = 0, base - 1 do
    for i = 0, base - row - 1 do
      local x = (i - (base - row - 1) / 2) * 1.0
      local box = world:add_box{ width = 1, height = 1, position = {x, 0.5 + row} }
      built[#built + 1] = { body = box, at = box.position }
    end
  end
  built[#built].body.name = "top"
end

function Check(world)
  local worst = 0
  for _, b in ipairs(built) do worst = math.max(worst, (b.body.position - b.at):length()) end
  print(string.format("largest displacement of a box after %g s: %.2e m", world.time, worst))
  check.less("largest displacement of a box", worst, 0.01)
  local top = world:find("top")
  check.near("top box height", top.position.y, base - 0.5, 0.01)
  check.near("top box x", top.position.x, 0, 0.01)
end
